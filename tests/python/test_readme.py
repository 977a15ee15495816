"""README.md's examples are the code that the tests run."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readme_cpp_example_is_the_compiled_consumer():
    readme = (ROOT / "README.md").read_text()
    consumer = (ROOT / "tests/packaging/consumer.cpp").read_text()
    example = consumer.split("// README example begin\n")[1].split("// README example end\n")[0]
    blocks = re.findall(r"```cpp\n(.*?)```", readme, re.S)
    assert any(example in b for b in blocks), "README's C++ example differs from tests/packaging/consumer.cpp"


def test_readme_problem_file_loads(tmp_path):
    import pytest

    pytest.importorskip("yaml")
    from pathpace.problem_file import load_problem

    readme = (ROOT / "README.md").read_text()
    yaml_block = re.findall(r"```yaml\n(.*?)```", readme, re.S)[0]
    f = tmp_path / "p.yaml"
    f.write_text(yaml_block)
    spec = load_problem(f)
    assert spec.robot.nq == 7 and spec.solve().ok


def test_readme_first_python_example_runs_as_pasted():
    readme = (ROOT / "README.md").read_text()
    block = re.findall(r"```python\n(.*?)```", readme, re.S)[0]
    scope = {}
    exec(compile(block, "README.md", "exec"), scope)  # noqa: S102 - the README's own example
    assert scope["res"].ok and abs(scope["res"].duration - 2.8189) < 1e-3  # the value the README prints
    assert set(scope["samples"]) == {"t", "q", "qd", "qdd"}


def test_readme_infeasible_example_prints_what_the_readme_says():
    """The infeasible Panda of the README, run as pasted (it needs example-robot-data): the message and the
    relaxation are the ones its comments show."""
    import numpy as np
    import pytest

    import pathpace as pp

    from pathpace.robots import example_robot_data_dir

    try:
        example_robot_data_dir()
    except FileNotFoundError:
        pytest.skip("example-robot-data is not installed")
    readme = (ROOT / "README.md").read_text()
    (block,) = [b for b in re.findall(r"```python\n(.*?)```", readme, re.S) if "res.relaxation   #" in b]
    scope = {"np": np, "pp": pp}
    exec(compile(block, "README.md", "exec"), scope)  # noqa: S102 - the README's own example
    res = scope["res"]
    comment = re.search(r'res\.message\s+# "(.*?)"\n', block, re.S).group(1)
    assert res.message == " ".join(part.strip().lstrip("#").strip() for part in comment.splitlines())
    assert res.relaxation["torque"] == pytest.approx(2.0663, abs=1e-4) and res.relaxation["velocity"] == np.inf

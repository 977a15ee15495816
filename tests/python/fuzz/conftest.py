"""The fuzz run's budget and seed in pytest's header, so that a long run can be repeated."""

from fuzz_support import EXAMPLES_OVERRIDE, LONG, SEED


def pytest_report_header(config):
    budget = f"{EXAMPLES_OVERRIDE} examples per test" if EXAMPLES_OVERRIDE else "20x examples" if LONG else "default examples"
    return f"pathpace fuzz: {budget}, " + (f"seed {SEED} (PATHPACE_FUZZ_SEED={SEED} repeats it)" if SEED else "derandomised")


def pytest_terminal_summary(terminalreporter):
    # Also under -q (make fuzz-long), which leaves the header out.
    if SEED:
        terminalreporter.write_line(pytest_report_header(None))

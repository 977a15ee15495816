"""pytest puts the folder of each conftest.py on sys.path (import mode "prepend"): this one makes the shared
modules of this folder (helpers.py, oracles.py, contact_corpus.py) importable from tests in subfolders
(fuzz/), also when those run alone (`pytest tests/python/fuzz`)."""

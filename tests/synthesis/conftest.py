"""The ``slow`` marker (a test that takes more than ~20 s; still run by the full suite)."""


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: takes more than about 20 s (still part of the full suite)")

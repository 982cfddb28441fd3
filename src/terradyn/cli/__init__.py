"""The ``terradyn`` command line (``python -m terradyn``)."""

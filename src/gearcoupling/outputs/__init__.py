"""The files gearcoupling writes: one writer per stage and :func:`run`, the pipeline of
``gearcoupling run`` (every file the project can make for a spec, into one folder).

Each writer validates before it writes (no NaN, no half-written file) and returns the
paths it wrote; the commands only parse their options, call these and print. Each name is
imported from its module on first use (``__init__.pyi``).
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)

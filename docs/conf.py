"""Sphinx configuration of the gearlever documentation (``make docs``).

Built offline: no intersphinx inventories are fetched.  The gallery scripts in
``gallery/`` run at build time, so every picture is drawn by the installed code.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent / "src"))  # the tree being documented, also before an install
os.environ.setdefault("MPLBACKEND", "Agg")

import gearlever  # noqa: E402

project = "gearlever"
author = "the gearlever authors"
copyright = "gearlever authors"  # noqa: A001 - Sphinx's name
version = release = gearlever.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "cli_reference",
    "caps_table",
    "api_toplevel",
]

templates_path = ["_templates"]
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "gallery/*.py", "gallery/GALLERY_HEADER.rst"]
root_doc = "index"
default_role = "code"
nitpicky = False

# API reference: one page per module, generated from the docstrings.
autosummary_generate = True
autosummary_imported_members = False
autosummary_ignore_module_all = True  # a module page lists what the module defines
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types
autodoc_mock_imports: list[str] = []

numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set[str] = set()  # the house docstrings are numpydoc-like, not all complete
numpydoc_xref_param_type = False

html_theme = "alabaster"
html_title = f"gearlever {release}"
html_static_path = ["_static"]
html_css_files = ["custom.css"]
html_theme_options = {
    "description": "Kinematics, forces and synthesis of gear-lever mechanisms",
    "fixed_sidebar": True,
    "page_width": "1100px",
    "sidebar_width": "230px",
}
html_sidebars = {"**": ["about.html", "navigation.html", "searchbox.html"]}

sphinx_gallery_conf = {
    "examples_dirs": ["gallery"],
    "gallery_dirs": ["auto_gallery"],
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "plot_gallery": "True",
    "capture_repr": (),  # the scripts' pictures and prints, not the reprs of returned Axes
}

"""Sphinx configuration of adhbem's documentation site (``./run docs`` builds it into
build/docs/html, warnings as errors).

The pages are Markdown (MyST); the tutorials are the Python scripts of tutorials/ (sphinx-gallery
runs them and keeps their figures); the option table, the C API and the Python API are made from
the code when the site is built (docs/_ext/: adhbem_options, adhbem_capi; autodoc with numpydoc),
so they cannot drift from it. The tutorials and the references import the package from python/
with the build that ADHBEM_BUILD names (./run docs sets it).
"""
import os
import sys

DOCS = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(DOCS)
sys.path.insert(0, os.path.join(DOCS, "_ext"))
sys.path.insert(0, os.path.join(ROOT, "python"))
os.environ.setdefault("ADHBEM_BUILD", os.path.join(ROOT, "build"))
os.environ.setdefault("MPLBACKEND", "Agg")

import adhbem  # noqa: E402  (the version; the solver side is imported by the references)
from sphinx_gallery.sorting import FileNameSortKey  # noqa: E402

project = "adhbem"
author = "the adhbem developers"
copyright = "2026, the adhbem developers (BSD 2-Clause licence)"
release = adhbem.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "adhbem_capi",
    "adhbem_options",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "tutorials/*.ipynb", "tutorials/*.py.md5", "tutorials/*.zip"]
myst_heading_anchors = 3          # [text](page.md#a-heading) links resolve
suppress_warnings = ["myst.header"]  # pages that start at ## under a generated title

html_theme = "furo"
html_title = f"adhbem {release}"
html_static_path = []
html_show_sourcelink = False

# Python API: numpydoc sections, no type hints repeated in signatures
autodoc_typehints = "none"
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

# Tutorials: the scripts of tutorials/ run when the site is built, their figures kept.
# ADHBEM_TUTORIAL_QUICK (set by the test suite) makes them small; the site runs them in full.
sphinx_gallery_conf = {
    "examples_dirs": [os.path.join(ROOT, "tutorials")],
    "gallery_dirs": ["tutorials"],
    "filename_pattern": r"/tutorial_",
    "ignore_pattern": r"__init__\.py|/_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": FileNameSortKey,
    "abort_on_example_error": True,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "capture_repr": (),
    "show_memory": False,
}

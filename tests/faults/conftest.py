"""The fault tests' interposer, failwrite.c (a disk that fills up, fails or holds a write), built
once for the folder."""
import os
import shutil
import subprocess

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.fixture(scope="session")
def failwrite(tmp_path_factory):
    cc = shutil.which("cc") or shutil.which("gcc")
    if not cc:
        pytest.skip("no C compiler for the interposer")
    lib = tmp_path_factory.mktemp("failwrite") / "failwrite.so"
    subprocess.run([cc, "-shared", "-fPIC", "-O1", "-o", str(lib), os.path.join(HERE, "failwrite.c"), "-ldl"], check=True)
    return str(lib)

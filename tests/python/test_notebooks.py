"""The notebooks of examples/notebooks: stored without outputs, and each executed from start to end by nbconvert
(Debian's jupyter-nbconvert and python3-ipykernel), with no cell failing and each drawing its figures. Needs
PYTHONPATH to reach this build's hubbeam (the kernel inherits it)."""
import glob
import json
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE = os.environ["SOURCE_DIR"]
NOTEBOOKS = sorted(glob.glob(os.path.join(SOURCE, "examples", "notebooks", "*.ipynb")))


class Notebooks(unittest.TestCase):
    def test_three_notebooks_stored_without_outputs(self):
        self.assertEqual([os.path.basename(n) for n in NOTEBOOKS],
                         ["campbell_blade.ipynb", "spinup_methods.ipynb", "tune_controller.ipynb"])
        for path in NOTEBOOKS:
            with open(path, encoding="utf-8") as f:
                nb = json.load(f)
            for cell in nb["cells"]:
                if cell["cell_type"] == "code":
                    self.assertEqual((cell["outputs"], cell["execution_count"]), ([], None), os.path.basename(path))

    def test_each_runs_to_its_end_and_draws(self):
        try:
            import nbconvert  # noqa: F401
            import ipykernel  # noqa: F401
        except ImportError as e:
            self.fail(f"the notebooks run with nbconvert and ipykernel: apt-get install jupyter-nbconvert "
                      f"python3-ipykernel ({e})")
        with tempfile.TemporaryDirectory() as d:
            for path in NOTEBOOKS:
                with self.subTest(notebook=os.path.basename(path)):
                    done = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute",
                                           "--ExecutePreprocessor.timeout=120", "--output-dir", d, path],
                                          capture_output=True, text=True,
                                          env=dict(os.environ, PYDEVD_DISABLE_FILE_VALIDATION="1"))
                    self.assertEqual(done.returncode, 0, done.stderr[-3000:])
                    with open(os.path.join(d, os.path.basename(path)), encoding="utf-8") as f:
                        outputs = [o for c in json.load(f)["cells"] for o in c.get("outputs", [])]
                    self.assertFalse([o for o in outputs if o["output_type"] == "error"])
                    figures = [o for o in outputs if "image/png" in o.get("data", {})]
                    self.assertGreaterEqual(len(figures), 2)


if __name__ == "__main__":
    unittest.main()

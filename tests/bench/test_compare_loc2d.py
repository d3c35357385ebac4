#!/usr/bin/env python3
"""bench/compare-loc2d without iris_lama: its refusals of a wrong source folder, the log list it
takes from a data folder and the table it prints. The comparison itself needs the peer's source
and runs by hand (BENCHMARKS.md, "Against a scan matcher")."""
import importlib.machinery
import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench",
                      "compare-loc2d")


def load_script():
    loader = importlib.machinery.SourceFileLoader("compare_loc2d", SCRIPT)
    spec = importlib.util.spec_from_loader("compare_loc2d", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


CL = load_script()


def run(*argv):
    return subprocess.run([sys.executable, SCRIPT, *argv], capture_output=True, text=True)


class SourceFolder(unittest.TestCase):
    def test_missing_folder_says_where_to_get_iris_lama(self):
        proc = run("--loc2d-source", "/nonexistent/iris_lama")
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("no such folder", proc.stderr)
        self.assertIn("https://github.com/iris-ua/iris_lama", proc.stderr)

    def test_a_folder_that_is_not_iris_lama_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            proc = run("--loc2d-source", d)
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("is not an iris_lama source folder (no include/lama/loc2d.h)", proc.stderr)

    def test_no_folder_at_all(self):
        proc = run()
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("--loc2d-source DIR is required", proc.stderr)


class Logs(unittest.TestCase):
    def test_takes_the_accuracy_table_logs_present_in_the_data_folder(self):
        with tempfile.TemporaryDirectory() as data:
            os.makedirs(os.path.join(data, "intel"))
            for f in ("intel.yaml", "intel.clf", "intel.gt.tum"):
                open(os.path.join(data, "intel", f), "w").close()
            found = CL.logs_with_reference(data, ".")
        self.assertEqual([name for name, _ in found], ["intel"])
        self.assertTrue(found[0][1]["ref"].endswith("intel/intel.gt.tum"))

    def test_every_accuracy_table_tracking_log_is_compared(self):
        names = [row[0] for row in CL.AT.TRACKING_LOGS]
        self.assertIn("intel", names)
        self.assertGreaterEqual(len(names), 5)


class Table(unittest.TestCase):
    def runs(self, ate, p50, lost=False):
        return [{"ate": ate, "p50": p50 + k, "p99": 2 * p50 + k, "lost": lost, "threads": 2}
                for k in (0.0, 0.1, 0.2)]

    def test_a_row_holds_medians_over_rounds_and_who_was_lost(self):
        row = CL.summarize("intel", {"loc2d": self.runs(0.033, 0.2, lost=True),
                                     "mote1": self.runs(0.049, 0.5), "mote": self.runs(0.049, 0.3)})
        self.assertEqual(row, ["intel", "0.033", "0.049", "0.30 / 0.50", "0.60 / 1.10",
                               "0.40 / 0.70", "Loc2D"])

    def test_a_mote_ate_that_differs_between_thread_counts_is_flagged(self):
        row = CL.summarize("intel", {"loc2d": self.runs(0.033, 0.2),
                                     "mote1": self.runs(0.049, 0.5), "mote": self.runs(0.050, 0.3)})
        self.assertEqual(row[2], "0.049 (varies)")
        self.assertEqual(row[-1], "none")

    def test_markdown(self):
        text = CL.table([["intel", "0.033", "0.049", "a", "b", "c", "none"]], 2)
        lines = text.splitlines()
        self.assertEqual(len(lines), 3)
        self.assertIn("mote p50 / p99 ms (2 threads)", lines[0])
        self.assertEqual(lines[1].count("|"), lines[0].count("|"))


if __name__ == "__main__":
    unittest.main()

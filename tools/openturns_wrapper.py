"""lsi as an OpenTURNS function: a whole sample of points is evaluated by one `lsi sweep` run.

    import openturns as ot
    from openturns_wrapper import lsi_function       # tools/ on sys.path

    f = lsi_function("my-study.json",
                     inputs=["/landslide/velocity_m_s", "/barrier/base_friction"],
                     outputs=["analytical/peak_force", "analytical/final_displacement"])
    X = ot.ComposedDistribution([ot.Uniform(4, 8), ot.Uniform(0.3, 0.7)]).getSample(100000)
    Y = f(X)                                           # one lsi run for the 100000 points

The study file is a template (tools/lsi_points.py): its scene and methods are used, the points
are the sample's rows; `inputs` are JSON pointers of scene values, `outputs` lsi's output
columns "<method>/<output>". lsi checks every value as it checks a scene: a point out of range
raises lsi_points.LsiError with lsi's message (file, row, column, value, allowed range). A
sample that lsi ran but could not evaluate (an MPM run that failed) has NaN outputs.
"""
import os
import sys

import openturns as ot

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lsi_points  # noqa: E402


class LsiFunction(ot.OpenTURNSPythonFunction):
    """An ot.OpenTURNSPythonFunction: _exec_sample runs the whole sample in one lsi call, _exec
    one point. `lsi_runs` counts the lsi runs made."""

    def __init__(self, study, inputs, outputs, lsi=None, work_dir=None):
        super().__init__(len(inputs), len(outputs))
        self.setInputDescription(list(inputs))
        self.setOutputDescription(list(outputs))
        self._study = study
        self._inputs = list(inputs)
        self._outputs = list(outputs)
        self._lsi = lsi_points.find_lsi(lsi)
        self._work_dir = work_dir
        self.lsi_runs = 0

    def _exec_sample(self, X):
        try:  # a sample as a buffer of doubles (what OpenTURNS passes), fast through numpy
            import numpy
            rows = numpy.asarray(X, dtype=float).tolist()
        except ImportError:
            rows = [[float(v) for v in x] for x in X]
        if not rows:
            return []
        self.lsi_runs += 1
        table = lsi_points.evaluate(self._study, self._inputs, rows, lsi=self._lsi,
                                    work_dir=self._work_dir)
        status = table.column("status")
        values = table.values(self._outputs)
        nan = float("nan")
        return [v if s == 0 else [nan] * len(v) for v, s in zip(values, status)]

    def _exec(self, x):
        return self._exec_sample([list(x)])[0]


def lsi_function(study, inputs, outputs, lsi=None, work_dir=None):
    """An ot.Function of lsi (its implementation, an LsiFunction, is returned beside it by
    lsi_function_and_runner)."""
    return lsi_function_and_runner(study, inputs, outputs, lsi, work_dir)[0]


def lsi_function_and_runner(study, inputs, outputs, lsi=None, work_dir=None):
    """(ot.Function, LsiFunction): the function, and the object behind it (lsi_runs)."""
    runner = LsiFunction(study, inputs, outputs, lsi=lsi, work_dir=work_dir)
    return ot.Function(runner), runner

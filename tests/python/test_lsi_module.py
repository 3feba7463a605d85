"""The Python module lsi (python/) against the lsi command: its closed forms and run() give what
`lsi run` gives for the same scene, bad input raises ValueError naming the field, and 1e5 points
evaluate in one call. Run by run_pytest.py (ctest python_module), which puts the built module on
the path and names the lsi executable, the source tree and a work folder in LSI_EXE,
LSI_SOURCE_DIR and LSI_WORK_DIR.
"""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import lsi

LSI = os.environ["LSI_EXE"]
SOURCE = os.environ["LSI_SOURCE_DIR"]
WORK = os.environ["LSI_WORK_DIR"]

# The closed forms of the module go through the batched kernel of `lsi sweep`, `lsi run` through
# the scalar methods: the same formulas, whose multiply-adds the compiler may contract
# differently. run() and `lsi run` call the same functions: equal but for that.
REL = 1e-12

# Closed-form scenes of every kind: the momentum-consistent and the paper's barrier, free and
# fixed, a barrier given by its mass, a rectangular landslide, the parser's default methods, a
# calibrated lambda and tau.
CLOSED_FORM_SCENES = [
    "scenes/reference/L1-B1.json",
    "scenes/reference/L2-B3-fixed.json",
    "scenes/former-reference/L1-B1.json",
    "scenes/former-reference/L3-B2.json",
    "scenes/examples/rectangle-fixed.json",
    "scenes/examples/minimal.json",
    "scenes/tutorial/my-scene-calibrated.json",
]
TINY_MPM_SCENE = "tests/install/tiny-impact.json"
# Wall-clock measurements of a run: not results, they differ from run to run.
TIMINGS = {"solver_seconds", "particle_updates_per_second"}
# The momentum-consistent barrier's largest velocity is the largest at the ends of its adaptive
# integrator's steps: where the steps fall moves with the last bits of the error estimate (the
# same formulas, contracted differently in the module and in lsi), and near the maximum the value
# moves with the square of that shift, not with the integrator's error.
REL_STEP_SAMPLED = {"largest_barrier_velocity": 1e-5}


def scene_path(relative):
    return os.path.join(SOURCE, relative)


def load(relative):
    with open(scene_path(relative), encoding="utf-8") as f:
        return json.load(f)


def lsi_run(scene, *options):
    """`lsi run SCENE --format json OPTIONS...`: the summary, {method: {name: value}}."""
    out = subprocess.run([LSI, "run", scene, "--format", "json", *options], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)


def close(a, b, rel=REL):
    if math.isinf(a) or math.isinf(b) or math.isnan(a) or math.isnan(b):
        return a == b or (math.isnan(a) and math.isnan(b))
    return abs(a - b) <= rel * max(abs(a), abs(b))


def summary_value(summary, name):
    """A value of the JSON summary: null is a barrier that never stops (+inf)."""
    v = summary[name]
    return math.inf if v is None else v


# (a) The closed forms over arrays against `lsi run` of each point's scene.

@pytest.mark.parametrize("relative", CLOSED_FORM_SCENES)
def test_closed_forms_match_lsi_run(relative):
    scene = scene_path(relative)
    expected = lsi_run(scene, "--methods", "empirical,analytical")
    got = lsi.closed_forms(scene, methods=["empirical", "analytical"])
    assert set(got) == {"empirical", "analytical"}
    for method, outputs in got.items():
        assert set(outputs) == {"peak_force", "rise_time", "impact_duration",
                                "final_displacement"}
        for name, values in outputs.items():
            assert values.shape == (1,) and values.dtype == np.float64
            assert close(values[0], summary_value(expected[method], name)), (method, name)


@pytest.mark.parametrize("relative", CLOSED_FORM_SCENES[:4])
def test_closed_forms_over_arrays_match_lsi_run_per_point(relative):
    doc = load(relative)
    velocity = np.array([2.5, 4.0, 7.5])
    thickness = np.array([1.0, 1.75, 2.5])
    base_friction = 0.35  # a number broadcasts over the arrays
    got = lsi.closed_forms(doc, methods="empirical,analytical", velocity_m_s=velocity,
                           thickness_m=thickness, base_friction=base_friction)
    for i in range(len(velocity)):
        expected = lsi_run(scene_path(relative), "--methods", "empirical,analytical",
                           "--set", f"/landslide/velocity_m_s={velocity[i]!r}",
                           "--set", f"/landslide/thickness_m={thickness[i]!r}",
                           "--set", f"/barrier/base_friction={base_friction!r}")
        for method, outputs in got.items():
            for name, values in outputs.items():
                assert values.shape == (3,)
                assert close(values[i], summary_value(expected[method], name)), (method, name, i)


def test_single_method_functions_and_default_methods():
    doc = load("scenes/former-reference/L1-B1.json")
    both = lsi.closed_forms(doc, velocity_m_s=[3.0, 6.0])  # the scene selects both
    for method, function in (("empirical", lsi.empirical), ("analytical", lsi.analytical)):
        one = function(doc, velocity_m_s=[3.0, 6.0])
        for name in one:
            np.testing.assert_array_equal(one[name], both[method][name])


def test_closed_forms_without_a_scene_match_the_scene_file():
    doc = load("scenes/examples/rectangle-fixed.json")
    land, barrier = doc["landslide"], doc["barrier"]
    got = lsi.closed_forms(
        thickness_m=land["thickness_m"], velocity_m_s=land["velocity_m_s"],
        density_kg_m3=land["density_kg_m3"], length_m=land["shape"]["length_m"],
        height_m=barrier["height_m"], base_width_m=barrier["base_width_m"],
        top_width_m=barrier["top_width_m"], face_angle_deg=barrier["face_angle_deg"],
        barrier_mass_kg_per_m=barrier["mass_kg_per_m"], fixed=barrier["fixed"],
        analytical_lambda=doc["methods"]["analytical"]["lambda"],
        analytical_tau=doc["methods"]["analytical"]["tau"])
    expected = lsi.closed_forms(doc)
    for method in ("empirical", "analytical"):
        for name in expected[method]:
            np.testing.assert_array_equal(got[method][name], expected[method][name])


def test_input_names_are_the_scene_keys():
    for name, pointer in lsi.closed_form_inputs.items():
        key = pointer.rsplit("/", 1)[1]
        assert name.endswith(key), (name, pointer)
    assert lsi.closed_form_inputs["barrier_density_kg_m3"] == "/barrier/density_kg_m3"
    assert lsi.closed_form_inputs["analytical_tau"] == "/methods/analytical/tau"


# (b) run() against `lsi run` of the same scene: every scalar of the summary and every history
# of the HDF5 result.

def check_run_matches(doc, name, *options):
    scene = os.path.join(WORK, name + ".json")
    h5 = os.path.join(WORK, name + ".h5")
    with open(scene, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    if os.path.exists(h5):
        os.remove(h5)
    expected = lsi_run(scene, "--out", h5, *options)
    methods = None
    if options:
        methods = options[options.index("--methods") + 1].split(",")
    got = lsi.run(doc, methods=methods)
    assert set(got) == set(expected)
    for method, summary in expected.items():
        result = got[method]
        for key, value in summary.items():
            if key in ("end_state", "status", "barrier_model"):
                assert result[key] == value, (method, key)
            elif key not in TIMINGS:
                assert close(result["scalars"][key], summary_value(summary, key),
                             REL_STEP_SAMPLED.get(key, REL)), (method, key)
        given = {k for k, v in result["scalars"].items() if not math.isnan(v)}
        assert given == set(summary) - {"end_state", "status", "barrier_model"}
    h5py = pytest.importorskip("h5py")
    with h5py.File(h5, "r") as f:
        for method in expected:
            # The histories: the datasets of the method's group on its time axis.
            group = f[method]
            stored_histories = {k for k, d in group.items() if isinstance(d, h5py.Dataset)
                                and d.shape == group["time"].shape}
            histories = got[method]["histories"]
            assert set(histories) == stored_histories, method
            for key, values in histories.items():
                stored = group[key][:]
                scale = max(np.max(np.abs(stored)), np.finfo(float).tiny)
                assert np.max(np.abs(values - stored)) <= REL * scale, (method, key)
                assert got[method]["units"][key] == group[key].attrs["units"], (method, key)
    return got


@pytest.mark.parametrize("relative", CLOSED_FORM_SCENES + ["scenes/examples/literature-mixed.json"])
def test_run_closed_forms_match_lsi_run(relative):
    doc = load(relative)
    methods = [m for m in ("empirical", "analytical", "literature")
               if m in doc.get("methods", {"empirical": {}, "analytical": {}})]
    got = check_run_matches(doc, os.path.basename(relative)[:-5], "--methods", ",".join(methods))
    for method in methods:
        assert got[method]["units"]["peak_force"] == "N/m"
        if method != "literature":  # a peak force only, no history
            assert got[method]["units"]["time"] == "s"


def test_run_tiny_mpm_scene_matches_lsi_run():
    # One OpenMP thread (ctest's environment): the run is then the same in both.
    assert os.environ.get("OMP_NUM_THREADS") == "1"
    got = check_run_matches(load(TINY_MPM_SCENE), "tiny-impact")
    assert list(got) == ["empirical", "analytical", "mpm"]  # in the order they ran
    mpm = got["mpm"]
    assert mpm["status"] == "finished"
    assert mpm["scalars"]["steps"] > 0
    assert len(mpm["histories"]["time"]) == len(mpm["histories"]["force"]) > 1


def test_run_takes_a_path_and_methods():
    got = lsi.run(scene_path(TINY_MPM_SCENE), methods="analytical")
    assert list(got) == ["analytical"]
    expected = lsi_run(scene_path(TINY_MPM_SCENE), "--methods", "analytical")
    assert close(got["analytical"]["scalars"]["peak_force"],
                 expected["analytical"]["peak_force"])


# The snapshots of the material points: run() returns what `lsi run --out` writes under
# /mpm/snapshots, the vectors without the file's z = 0 column. One thread: the same run in both,
# equal but for round-off.
SNAPSHOT_FIELDS = {"id", "material", "position", "displacement", "velocity", "stress", "mass",
                   "volume", "volumetric_strain", "deviatoric_strain", "plastic_work"}


def small_dam_break():
    """A coarse, short dam break (an mpm_case verification scene): water, no barrier."""
    doc = load("scenes/verification/dam-break-front.json")
    doc["name"] = "small-dam-break"
    doc["methods"]["mpm"].update(cell_size_m=0.01, end_time_s=0.05, output_interval_s=0.005)
    return doc


@pytest.mark.parametrize("name, interval", [("tiny-impact", 0.08), ("small-dam-break", 0.02)])
def test_run_returns_the_snapshots_lsi_run_writes(name, interval):
    assert os.environ.get("OMP_NUM_THREADS") == "1"
    h5py = pytest.importorskip("h5py")
    doc = load(TINY_MPM_SCENE) if name == "tiny-impact" else small_dam_break()
    doc["methods"]["mpm"]["snapshot_interval_s"] = interval
    if name == "tiny-impact":  # the face's bands too
        doc["methods"]["mpm"]["face_band_m"] = 0.5
    scene = os.path.join(WORK, name + "-snapshots.json")
    h5 = os.path.join(WORK, name + "-snapshots.h5")
    with open(scene, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    for old in (h5, h5[:-3] + ".xdmf"):
        if os.path.exists(old):
            os.remove(old)
    subprocess.run([LSI, "--progress", "none", "run", scene, "--out", h5], check=True,
                   capture_output=True)
    mpm = lsi.run(doc, methods="mpm")["mpm"]
    snapshots = mpm["snapshots"]
    # At t = 0, at the first output reaching each multiple of the interval before the end time,
    # and at the end of the run.
    end = mpm["histories"]["time"][-1]
    multiples = math.floor(end / interval * (1 + 1e-9))
    assert end > multiples * interval  # the end is not a multiple: a snapshot of its own
    assert len(snapshots) == multiples + 2
    assert snapshots[0]["time"] == 0.0 and snapshots[-1]["time"] == end
    step = mpm["scalars"]["end_time"] / mpm["scalars"]["steps"] * 10  # ten mean steps
    for k in range(1, multiples + 1):
        assert k * interval <= snapshots[k]["time"] * (1 + 1e-12) < k * interval + step, k
    with h5py.File(h5, "r") as f:
        stored = f["mpm/snapshots"]
        assert stored.attrs["count"] == len(snapshots)
        assert mpm["snapshot_materials"] == stored.attrs["materials"].split(",")
        for k, snapshot in enumerate(snapshots):
            group = stored[f"{k:06d}"]
            assert set(snapshot) - {"time"} == set(group), k
            assert SNAPSHOT_FIELDS <= set(snapshot)
            assert ("barrier_outline" in snapshot) == (name == "tiny-impact")
            assert ("face_pressure" in snapshot) == (name == "tiny-impact")
            assert math.isclose(snapshot["time"], group.attrs["time"], rel_tol=REL)
            n = len(snapshot["id"])
            assert n > 0
            for key, values in snapshot.items():
                if key == "time":
                    continue
                data = group[key][:]
                assert mpm["snapshot_units"][key] == group[key].attrs["units"], key
                if data.ndim == 2 and data.shape[1] == 3:  # x, y and the file's z = 0
                    assert np.all(data[:, 2] == 0.0), key
                    data = data[:, :2]
                assert values.shape == data.shape and values.dtype == data.dtype, (k, key)
                if values.dtype == np.int64:
                    np.testing.assert_array_equal(values, data, err_msg=f"{k} {key}")
                else:
                    scale = max(np.max(np.abs(data)), np.finfo(float).tiny)
                    assert np.max(np.abs(values - data)) <= REL * scale, (k, key)
    # Nothing asked for, nothing returned.
    del doc["methods"]["mpm"]["snapshot_interval_s"]
    assert "snapshots" not in lsi.run(doc, methods="mpm")["mpm"]


# (c) Errors: ValueError naming the field, its value or index, and the allowed range.

def test_negative_and_nan_inputs_name_the_field():
    doc = load("scenes/former-reference/L1-B1.json")
    with pytest.raises(ValueError, match=r"^thickness_m = -1: must be > 0$"):
        lsi.closed_forms(doc, thickness_m=-1.0)
    with pytest.raises(ValueError, match=r"^thickness_m\[2\] = -0.5: must be > 0$"):
        lsi.empirical(doc, thickness_m=[1.0, 2.0, -0.5])
    with pytest.raises(ValueError, match=r"^velocity_m_s\[1\] = nan: must be finite and > 0$"):
        lsi.analytical(doc, velocity_m_s=[3.0, math.nan])
    with pytest.raises(ValueError, match=r"^analytical_tau = 1: must be in \(0, 1\)$"):
        lsi.analytical(doc, analytical_tau=1.0)
    with pytest.raises(ValueError, match=r"^body_squares = 2.5: must be an integer in \[0, "):
        lsi.empirical(doc, body_squares=2.5)


def test_checks_across_fields_give_the_parsers_message_and_index():
    doc = load("scenes/former-reference/L1-B1.json")
    base = doc["barrier"]["base_width_m"]
    with pytest.raises(ValueError, match=r"^index 1: barrier\.top_width_m = .*: must be in "
                                         r"\[0, base_width_m = "):
        lsi.closed_forms(doc, top_width_m=[0.5 * base, 2.0 * base])
    with pytest.raises(ValueError, match=r"^index 2: barrier\.face_angle_deg = 10"):
        lsi.closed_forms(doc, face_angle_deg=[90.0, 80.0, 10.0])


def test_run_refuses_invalid_scenes_with_the_parsers_message():
    doc = load(TINY_MPM_SCENE)
    doc["landslide"]["thickness_m"] = -2.0
    with pytest.raises(ValueError, match=r"^landslide\.thickness_m = -2(\.0)?: must be > 0"):
        lsi.run(doc)
    doc["landslide"]["thickness_m"] = math.nan
    with pytest.raises(ValueError, match=r"^landslide\.thickness_m = nan: must be finite"):
        lsi.run(doc)
    doc["landslide"]["thickness_m"] = 1.0
    doc["landslide"]["thicknes_m"] = 1.0
    with pytest.raises(ValueError, match=r"^landslide\.thicknes_m: unknown key"):
        lsi.run(doc)


def test_bad_arguments():
    doc = load("scenes/former-reference/L1-B1.json")
    with pytest.raises(TypeError, match=r"^thicknes_m: not a scene field"):
        lsi.closed_forms(doc, thicknes_m=1.0)
    with pytest.raises(ValueError, match=r"^young_modulus_mpa: read by the MPM only"):
        lsi.closed_forms(doc, young_modulus_mpa=3.0)
    with pytest.raises(ValueError, match=r"^velocity_m_s has 3 values but thickness_m has 2"):
        lsi.closed_forms(doc, thickness_m=[1.0, 2.0], velocity_m_s=[1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"^thickness_m: a 2-D array"):
        lsi.closed_forms(doc, thickness_m=np.ones((2, 2)))
    with pytest.raises(ValueError, match=r"^methods: literature: unknown method"):
        lsi.closed_forms(doc, methods="literature")
    with pytest.raises(ValueError, match=r"^methods: mpm: the scene has no methods\.mpm block"):
        lsi.run(load("scenes/examples/minimal.json"), methods=["mpm"])
    with pytest.raises(ValueError, match=r"^barrier\.face_angle_deg: missing"):
        lsi.empirical(thickness_m=2.0, velocity_m_s=5.0, density_kg_m3=1800.0, body_squares=4,
                      height_m=3.0, base_width_m=3.0, top_width_m=1.0,
                      barrier_density_kg_m3=2400.0)


# (d) Vectorised: 1e5 points in one call, each what a call with its scalars gives.

def test_1e5_points_in_one_call_equal_scalar_calls():
    doc = load("scenes/former-reference/L1-B1.json")
    rng = np.random.default_rng(7)
    n = 100000
    velocity = rng.uniform(2.0, 9.0, n)
    thickness = rng.uniform(1.0, 3.0, n)
    base_friction = rng.uniform(0.2, 0.8, n)
    got = lsi.closed_forms(doc, velocity_m_s=velocity, thickness_m=thickness,
                           base_friction=base_friction)
    for outputs in got.values():
        for values in outputs.values():
            assert values.shape == (n,)
            assert np.all(np.isfinite(values) | (values == math.inf))
    # Every 7th point (a scalar call parses its scene: a whole loop would take seconds): the
    # same kernel on the same inputs, to the last bit.
    for i in range(0, n, 7):
        one = lsi.closed_forms(doc, velocity_m_s=velocity[i], thickness_m=thickness[i],
                               base_friction=base_friction[i])
        for method, outputs in one.items():
            for name, values in outputs.items():
                assert values[0] == got[method][name][i], (method, name, i)

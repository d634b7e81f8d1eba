//! `restitution._core`: the compiled part of the Python package. Thin by design: it converts
//! NumPy columns into core cases, runs them with the GIL released, and returns NumPy columns.
//! Validation with friendly messages lives in the Python layer; whatever slips through is
//! still caught by the core and raised as `ValueError`.

use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use restitution_core as core;

/// Core errors as Python exceptions: a foreign error type needs a local newtype.
struct PyCoreError(core::Error, Option<usize>);

impl From<PyCoreError> for PyErr {
    fn from(e: PyCoreError) -> PyErr {
        match (e.0, e.1) {
            (err @ core::Error::InvalidParameter { .. }, None) => {
                PyValueError::new_err(err.to_string())
            }
            (err @ core::Error::InvalidParameter { .. }, Some(i)) => {
                PyValueError::new_err(format!("case {i}: {err}"))
            }
            (core::Error::Interrupted, _) => {
                pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted")
            }
        }
    }
}

/// Names of the per-case input columns (all float64 except `n` and `integrator`, int64).
const FLOAT_COLUMNS: [&str; 14] = [
    "theta_deg",
    "omega_in",
    "v",
    "mu",
    "gamma",
    "gamma_t",
    "E",
    "rho",
    "r",
    "phi0_deg",
    "dt_factor",
    "kn",
    "cn",
    "kt",
];

struct Columns<'py> {
    floats: Vec<PyReadonlyArray1<'py, f64>>,
    n: PyReadonlyArray1<'py, i64>,
    integrator: PyReadonlyArray1<'py, i64>,
}

fn get<'py, T: numpy::Element>(
    cols: &Bound<'py, PyDict>,
    name: &str,
) -> PyResult<PyReadonlyArray1<'py, T>> {
    let item = cols
        .get_item(name)?
        .ok_or_else(|| PyKeyError::new_err(format!("missing column `{name}`")))?;
    item.extract::<PyReadonlyArray1<'py, T>>().map_err(|_| {
        PyValueError::new_err(format!(
            "column `{name}` must be a 1-D contiguous {} array",
            std::any::type_name::<T>()
        ))
    })
}

fn parse_shape(n: i64, r: f64, vertices: Option<&[[f64; 2]]>) -> core::Result<core::Shape> {
    match (n, vertices) {
        (_, Some(v)) => {
            // Scale the template to circumradius r (the template itself has circumradius 1).
            let scaled: Vec<[f64; 2]> = v.iter().map(|p| [p[0] * r, p[1] * r]).collect();
            core::Shape::convex_polygon(&scaled)
        }
        (0, None) => core::Shape::disc(r),
        (n, None) if n >= 3 => core::Shape::regular_polygon(r, n as usize),
        (n, None) => Err(core::Error::invalid(
            "n",
            n,
            ">= 3 (or 0 for an exact disc)",
        )),
    }
}

fn parse_integrator(code: i64) -> core::Result<core::Integrator> {
    match code {
        0 => Ok(core::Integrator::Gear5),
        1 => Ok(core::Integrator::Verlet),
        2 => Ok(core::Integrator::Reference),
        c => Err(core::Error::invalid(
            "integrator",
            c,
            "code 0 (gear5), 1 (verlet) or 2 (reference)",
        )),
    }
}

fn build_cases(
    cols: &Columns,
    vertices: Option<&[[f64; 2]]>,
    normal_law: &str,
    inertia: &str,
) -> Result<Vec<core::Case>, PyCoreError> {
    let f: Vec<&[f64]> = cols
        .floats
        .iter()
        .map(|a| a.as_slice().expect("checked contiguous"))
        .collect();
    let n = cols.n.as_slice().expect("checked contiguous");
    let integ = cols.integrator.as_slice().expect("checked contiguous");
    let len = n.len();
    let inertia = match inertia {
        "shape" => core::InertiaModel::Shape,
        "sphere" => core::InertiaModel::Sphere,
        other => {
            return Err(PyCoreError(
                core::Error::invalid("inertia", format!("{other:?}"), "\"shape\" or \"sphere\""),
                None,
            ))
        }
    };
    (0..len)
        .map(|i| {
            let [theta, omega, v, mu, gamma, gamma_t, e, rho, r, phi0, dtf, kn, cn, kt] =
                std::array::from_fn(|k| f[k][i]);
            let build = || -> core::Result<core::Case> {
                let law = match normal_law {
                    "area" => core::NormalLaw::Area,
                    "linear" => core::NormalLaw::Linear { kn, cn },
                    other => {
                        return Err(core::Error::invalid(
                            "normal_law",
                            format!("{other:?}"),
                            "\"area\" or \"linear\"",
                        ))
                    }
                };
                let scene = core::Scene {
                    shape: parse_shape(n[i], r, vertices)?,
                    rho,
                    e_modulus: e,
                    gamma,
                    gamma_t,
                    mu,
                    kt: (!kt.is_nan()).then_some(kt),
                    normal_law: law,
                    inertia,
                    integrator: parse_integrator(integ[i])?,
                    dt_factor: dtf,
                    overlap: core::OverlapMethod::Auto,
                    max_steps: None,
                };
                Ok(core::Case {
                    scene,
                    init: core::Initial::from_angle(v, theta, omega, phi0),
                })
            };
            build().map_err(|e| PyCoreError(e, Some(i)))
        })
        .collect()
}

fn read_columns<'py>(cols: &Bound<'py, PyDict>) -> PyResult<Columns<'py>> {
    let floats = FLOAT_COLUMNS
        .iter()
        .map(|name| get::<f64>(cols, name))
        .collect::<PyResult<Vec<_>>>()?;
    let n = get::<i64>(cols, "n")?;
    let integrator = get::<i64>(cols, "integrator")?;
    let len = n.len();
    for (name, a) in FLOAT_COLUMNS.iter().zip(&floats) {
        if a.len() != len || a.as_slice().is_err() {
            return Err(PyValueError::new_err(format!(
                "column `{name}` must be contiguous with length {len}"
            )));
        }
    }
    if integrator.len() != len || n.as_slice().is_err() || integrator.as_slice().is_err() {
        return Err(PyValueError::new_err(format!(
            "columns `n` and `integrator` must be contiguous with length {len}"
        )));
    }
    Ok(Columns {
        floats,
        n,
        integrator,
    })
}

fn read_vertices(vertices: Option<PyReadonlyArray2<'_, f64>>) -> PyResult<Option<Vec<[f64; 2]>>> {
    let Some(v) = vertices else { return Ok(None) };
    let view = v.as_array();
    if view.ncols() != 2 {
        return Err(PyValueError::new_err(format!(
            "require `vertices` of shape (k, 2) (found shape {:?})",
            view.shape()
        )));
    }
    Ok(Some(
        view.rows()
            .into_iter()
            .map(|row| [row[0], row[1]])
            .collect(),
    ))
}

fn records_to_dict<'py>(py: Python<'py>, recs: &[core::Record]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    macro_rules! col {
        ($name:literal, $f:expr) => {
            out.set_item($name, PyArray1::from_vec(py, recs.iter().map($f).collect()))?;
        };
    }
    col!("e_n", |r| r.e_n);
    col!("e_t", |r| r.e_t.unwrap_or(0.0));
    col!("e_t_valid", |r| r.e_t.is_some());
    col!("e_kin", |r| r.e_kin);
    col!("omega_out", |r| r.omega_out);
    col!("beta", |r| r.beta.unwrap_or(0.0));
    col!("beta_valid", |r| r.beta.is_some());
    col!("rebound_angle_deg", |r| r.rebound_angle_deg);
    col!("vx_out", |r| r.vx_out);
    col!("vy_out", |r| r.vy_out);
    col!("contact_time", |r| r.contact_time);
    col!("steps", |r| r.steps as i64);
    col!("contacts", |r| r.contacts as i64);
    col!("max_depth", |r| r.max_depth);
    col!("max_area", |r| r.max_area);
    col!("slip_events", |r| r.slip_events as i64);
    col!("energy_in", |r| r.energy_in);
    col!("energy_out", |r| r.energy_out);
    col!("work_normal", |r| r.work_normal);
    col!("work_friction", |r| r.work_friction);
    col!("energy_residual", |r| r.energy_residual);
    col!("separated", |r| r.separated);
    col!("timed_out", |r| r.timed_out);
    Ok(out)
}

/// Applies the overlap path ("auto", "halfplane" or "parry") to every case; parry is
/// refused for a disc.
fn set_overlap(cases: &mut [core::Case], name: &str) -> Result<(), PyCoreError> {
    let method = core::OverlapMethod::from_name(name).map_err(|e| PyCoreError(e, None))?;
    for (i, case) in cases.iter_mut().enumerate() {
        method
            .check_shape(&case.scene.shape)
            .map_err(|e| PyCoreError(e, Some(i)))?;
        case.scene.overlap = method;
    }
    Ok(())
}

/// Runs one impact per row of `columns` (a dict of equal-length 1-D arrays) in parallel on
/// `threads` threads (0: all cores) with the GIL released. Returns a dict of result columns.
#[pyfunction]
#[pyo3(signature = (columns, vertices, normal_law, inertia, threads, overlap="auto"))]
fn run_cases<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    normal_law: &str,
    inertia: &str,
    threads: usize,
    overlap: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let cols = read_columns(columns)?;
    let vertices = read_vertices(vertices)?;
    let mut cases = build_cases(&cols, vertices.as_deref(), normal_law, inertia)?;
    set_overlap(&mut cases, overlap)?;
    let recs = py
        .detach(|| core::run_cases(&cases, threads))
        .map_err(|(i, e)| PyCoreError(e, Some(i)))?;
    records_to_dict(py, &recs)
}

/// Runs the single case in `columns` (length 1) and returns (record columns, trace columns).
#[pyfunction]
#[pyo3(signature = (columns, vertices, normal_law, inertia, overlap="auto"))]
fn trace_case<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    normal_law: &str,
    inertia: &str,
    overlap: &str,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyDict>)> {
    let cols = read_columns(columns)?;
    let vertices = read_vertices(vertices)?;
    let mut cases = build_cases(&cols, vertices.as_deref(), normal_law, inertia)?;
    set_overlap(&mut cases, overlap)?;
    let [case] = cases.as_slice() else {
        return Err(PyValueError::new_err(format!(
            "trace_case takes exactly one case (found {})",
            cases.len()
        )));
    };
    let (rec, tr) = py
        .detach(|| core::simulate_with_trace(&case.scene, &case.init))
        .map_err(|e| PyCoreError(e, None))?;
    let out = PyDict::new(py);
    for (name, col) in [
        ("t", tr.t),
        ("x", tr.x),
        ("y", tr.y),
        ("phi", tr.phi),
        ("vx", tr.vx),
        ("vy", tr.vy),
        ("omega", tr.omega),
        ("f_n", tr.f_n),
        ("f_t", tr.f_t),
        ("area", tr.area),
        ("depth", tr.depth),
        ("xi", tr.xi),
    ] {
        out.set_item(name, PyArray1::from_vec(py, col))?;
    }
    out.set_item("stick", PyArray1::from_vec(py, tr.stick))?;
    Ok((records_to_dict(py, &[rec])?, out))
}

/// Largest `dt_factor` each case of `columns` accepts: its integrator's stability bound for
/// that case's stiffness and damping (`restitution_core::max_dt_factor`; the column
/// `dt_factor` itself is ignored). With `explain`, also what sets each bound, in words.
/// Invalid other parameters raise `ValueError` naming the case.
#[pyfunction]
#[pyo3(signature = (columns, vertices, normal_law, inertia, explain=false))]
fn max_dt_factor_for<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    normal_law: &str,
    inertia: &str,
    explain: bool,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Option<Vec<String>>)> {
    let cols = read_columns(columns)?;
    let vertices = read_vertices(vertices)?;
    let cases = build_cases(&cols, vertices.as_deref(), normal_law, inertia)?;
    let mut bounds = Vec::with_capacity(cases.len());
    let mut reasons = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        if explain {
            let (b, why) =
                core::max_dt_factor_reason(&case.scene).map_err(|e| PyCoreError(e, Some(i)))?;
            bounds.push(b);
            reasons.push(why);
        } else {
            bounds.push(core::max_dt_factor(&case.scene).map_err(|e| PyCoreError(e, Some(i)))?);
        }
    }
    Ok((PyArray1::from_vec(py, bounds), explain.then_some(reasons)))
}

/// The compiled engine of the `restitution` package.
#[pymodule]
mod _core {
    #[pymodule_export]
    use super::{max_dt_factor_for, run_cases, trace_case};

    #[pymodule_init]
    fn init(m: &pyo3::Bound<'_, pyo3::types::PyModule>) -> pyo3::PyResult<()> {
        use pyo3::types::PyModuleMethods;
        m.add("__version__", env!("CARGO_PKG_VERSION"))?;
        Ok(())
    }
}

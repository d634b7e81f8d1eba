//! `restitution._core`: the compiled part of the Python package. Thin by design: it reads the
//! per-case columns of the engine's one schema by name (`restitution_core::CASE_COLUMNS`),
//! or one case as a row in that order, runs the cases with the GIL released and Ctrl-C
//! watched, and returns the record's columns by name (`restitution_core::RECORD_COLUMNS`), or
//! one record as a tuple in that order. Every rule lives in the core; its errors become
//! `restitution.RestitutionError` carrying the parameter, the value and the case.

use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyKeyError, PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyString, PyTuple};
use restitution_core as core;

mod interrupt;
use interrupt::interruptible;

/// A core error and the case it belongs to, as a Python exception (a foreign error type needs
/// a local newtype).
struct PyCoreError(core::Error, Option<usize>);

/// The value as Python sees it: a number when the core formatted one, else the text without
/// the quotes the core puts around names.
fn python_value(py: Python<'_>, value: &str) -> PyResult<Py<PyAny>> {
    Ok(match value.parse::<f64>() {
        Ok(x) => x.into_pyobject(py)?.into_any().unbind(),
        Err(_) => value
            .trim_matches('"')
            .into_pyobject(py)?
            .into_any()
            .unbind(),
    })
}

impl From<PyCoreError> for PyErr {
    fn from(PyCoreError(err, case): PyCoreError) -> PyErr {
        let core::Error::InvalidParameter {
            name,
            value,
            expected,
        } = &err
        else {
            // Error::Interrupted: the engine stopped because Ctrl-C set its token.
            return PyKeyboardInterrupt::new_err("interrupted");
        };
        Python::attach(|py| {
            let class = py
                .import("restitution.errors")?
                .getattr("RestitutionError")?;
            let args = (name, python_value(py, value)?, expected, case);
            Ok::<_, PyErr>(PyErr::from_value(class.call1(args)?))
        })
        .unwrap_or_else(|e| e)
    }
}

/// The cases of `columns` (a dict of equal-length float64 arrays, one per name of
/// `CASE_COLUMNS`), with the unit-circumradius `vertices` of a convex polygon if any.
fn read_cases(
    columns: &Bound<'_, PyDict>,
    vertices: (
        Option<PyReadonlyArray2<'_, f64>>,
        Option<PyReadonlyArray2<'_, f64>>,
    ),
) -> PyResult<Vec<core::Case>> {
    let arrays = core::CASE_COLUMNS
        .iter()
        .map(|name| column(columns, name))
        .collect::<PyResult<Vec<_>>>()?;
    let slices: Vec<&[f64]> = arrays
        .iter()
        .map(|a| a.as_slice().expect("checked"))
        .collect();
    let len = slices[0].len();
    if let Some(bad) = slices.iter().position(|s| s.len() != len) {
        return Err(PyValueError::new_err(format!(
            "column `{}` has length {} (expected {len}, as `{}`)",
            core::CASE_COLUMNS[bad],
            slices[bad].len(),
            core::CASE_COLUMNS[0]
        )));
    }
    let (particle, partner) = (read_vertices(vertices.0)?, read_vertices(vertices.1)?);
    let rows = (0..len).map(|i| std::array::from_fn(|k| slices[k][i]));
    core::cases_from_rows(rows, templates(&particle, &partner))
        .map_err(|(i, e)| PyCoreError(e, Some(i)).into())
}

fn column<'py>(cols: &Bound<'py, PyDict>, name: &str) -> PyResult<PyReadonlyArray1<'py, f64>> {
    let item = cols
        .get_item(name)?
        .ok_or_else(|| PyKeyError::new_err(format!("missing column `{name}`")))?;
    let array = item.extract::<PyReadonlyArray1<'py, f64>>().map_err(|_| {
        PyValueError::new_err(format!("column `{name}` must be a 1-D float64 array"))
    })?;
    if array.as_slice().is_err() {
        return Err(PyValueError::new_err(format!(
            "column `{name}` must be contiguous"
        )));
    }
    Ok(array)
}

/// The engine's view of the particle's and the partner's vertex templates.
fn templates<'a>(
    particle: &'a Option<Vec<[f64; 2]>>,
    partner: &'a Option<Vec<[f64; 2]>>,
) -> core::Templates<'a> {
    core::Templates {
        particle: particle.as_deref(),
        partner: partner.as_deref(),
    }
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

/// The records as columns named by `RECORD_COLUMNS`; an optional value also gets a boolean
/// column `<name>_valid` (false where it is undefined, its value column then holds 0).
fn records_to_dict<'py>(py: Python<'py>, recs: &[core::Record]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let cells: Vec<_> = recs.iter().map(core::Record::cells).collect();
    for (k, name) in core::RECORD_COLUMNS.iter().enumerate() {
        let first = cells.first().map(|c| c[k]);
        match first.unwrap_or(core::Cell::F64(0.0)) {
            core::Cell::F64(_) => out.set_item(name, floats(py, &cells, k))?,
            core::Cell::Opt(_) => {
                out.set_item(name, floats(py, &cells, k))?;
                let valid = cells
                    .iter()
                    .map(|c| matches!(c[k], core::Cell::Opt(Some(_))));
                out.set_item(format!("{name}_valid"), PyArray1::from_iter(py, valid))?;
            }
            core::Cell::Int(_) => out.set_item(
                name,
                PyArray1::from_iter(
                    py,
                    cells.iter().map(|c| match c[k] {
                        core::Cell::Int(n) => n as i64,
                        _ => 0,
                    }),
                ),
            )?,
            core::Cell::Name(_) => out.set_item(
                name,
                cells
                    .iter()
                    .map(|c| match c[k] {
                        core::Cell::Name(s) => s,
                        _ => "",
                    })
                    .collect::<Vec<_>>(),
            )?,
            core::Cell::Bool(_) => out.set_item(
                name,
                PyArray1::from_iter(
                    py,
                    cells.iter().map(|c| matches!(c[k], core::Cell::Bool(true))),
                ),
            )?,
        }
    }
    Ok(out)
}

fn floats<'py>(
    py: Python<'py>,
    cells: &[[core::Cell; core::RECORD_COLUMNS.len()]],
    k: usize,
) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_iter(
        py,
        cells.iter().map(|c| match c[k] {
            core::Cell::F64(x) | core::Cell::Opt(Some(x)) => x,
            _ => 0.0,
        }),
    )
}

/// Diagnostics of the last call on this thread that ran the engine (`run_cases`, `run_case`,
/// `trace_case`):
/// `engine_s`, the seconds the engine itself took (from its entry to its return, measured in
/// Rust), and `waits_after_engine`, how many times the call went back to wait for a poll after
/// the engine had returned (0 when the call ended as soon as its work did). For benchmarks and
/// tests of the binding's own cost; not part of the package's API.
#[pyfunction]
fn last_call_diagnostics(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let last = interrupt::last_call();
    let out = PyDict::new(py);
    out.set_item("engine_s", last.engine_s)?;
    out.set_item("waits_after_engine", last.waits_after_engine)?;
    Ok(out)
}

/// Runs one impact per row of `columns` in parallel on `threads` threads (0: all cores) with
/// the GIL released. Returns the record columns.
#[pyfunction]
#[pyo3(signature = (columns, vertices, threads, partner_vertices=None))]
fn run_cases<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    threads: usize,
    partner_vertices: Option<PyReadonlyArray2<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let cases = read_cases(columns, (vertices, partner_vertices))?;
    // One case, or one thread: the calling thread runs it (results do not depend on threads).
    let parallel = threads != 1 && cases.len() > 1;
    let threads = if parallel { threads } else { 1 };
    let recs = interruptible(py, parallel, |cancel| {
        core::run_cases_cancellable(&cases, threads, cancel)
    })?
    .map_err(|(i, e)| PyCoreError(e, Some(i)))?;
    records_to_dict(py, &recs)
}

/// The one case of `row` (a value per name of `CASE_COLUMNS`, in that order), as
/// [`read_cases`] reads a row of columns.
fn read_case(
    row: [f64; core::CASE_COLUMNS.len()],
    vertices: (
        Option<PyReadonlyArray2<'_, f64>>,
        Option<PyReadonlyArray2<'_, f64>>,
    ),
) -> PyResult<core::Case> {
    let (particle, partner) = (read_vertices(vertices.0)?, read_vertices(vertices.1)?);
    let mut cases = core::cases_from_rows(std::iter::once(row), templates(&particle, &partner))
        .map_err(|(i, e)| PyCoreError(e, Some(i)))?;
    Ok(cases.pop().expect("one row, one case"))
}

/// The record's values in `RECORD_COLUMNS` order, None where one is undefined.
fn record_tuple<'py>(py: Python<'py>, rec: &core::Record) -> PyResult<Bound<'py, PyTuple>> {
    let values = rec.cells().map(|cell| -> PyResult<Bound<'py, PyAny>> {
        Ok(match cell {
            core::Cell::F64(x) | core::Cell::Opt(Some(x)) => PyFloat::new(py, x).into_any(),
            core::Cell::Opt(None) => py.None().into_bound(py),
            core::Cell::Int(n) => n.into_pyobject(py)?.into_any(),
            core::Cell::Bool(b) => PyBool::new(py, b).to_owned().into_any(),
            core::Cell::Name(name) => PyString::new(py, name).into_any(),
        })
    });
    PyTuple::new(py, values.into_iter().collect::<PyResult<Vec<_>>>()?)
}

/// Runs the one impact of `row` (a value per name of `CASE_COLUMNS`, in that order) on this
/// thread with the GIL released; returns its record as a tuple in `RECORD_COLUMNS` order (None
/// where a value is undefined): one impact without a column per value either way.
#[pyfunction]
#[pyo3(signature = (row, vertices, partner_vertices=None))]
fn run_case<'py>(
    py: Python<'py>,
    row: [f64; core::CASE_COLUMNS.len()],
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    partner_vertices: Option<PyReadonlyArray2<'py, f64>>,
) -> PyResult<Bound<'py, PyTuple>> {
    let case = read_case(row, (vertices, partner_vertices))?;
    let rec = interruptible(py, false, |cancel| {
        core::simulate_cancellable(&case.scene, &case.init, cancel)
    })?
    .map_err(|e| PyCoreError(e, Some(0)))?;
    record_tuple(py, &rec)
}

/// Checks every rule of every case of `columns` without running it (in parallel, GIL
/// released); raises `RestitutionError` naming the first bad case.
#[pyfunction]
#[pyo3(signature = (columns, vertices, threads=0, partner_vertices=None))]
fn check_cases<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    threads: usize,
    partner_vertices: Option<PyReadonlyArray2<'py, f64>>,
) -> PyResult<()> {
    let cases = read_cases(columns, (vertices, partner_vertices))?;
    py.detach(|| core::check_cases(&cases, threads))
        .map_err(|(i, e)| PyCoreError(e, Some(i)).into())
}

/// Checks every rule of the one case of `row` (a value per name of `CASE_COLUMNS`, in that
/// order) without running it: what a `Scene` does once when it is built, without a column per
/// value (one array per column made that a third of the scene's cost).
#[pyfunction]
#[pyo3(signature = (row, vertices, partner_vertices=None))]
fn check_case<'py>(
    row: [f64; core::CASE_COLUMNS.len()],
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    partner_vertices: Option<PyReadonlyArray2<'py, f64>>,
) -> PyResult<()> {
    let case = read_case(row, (vertices, partner_vertices))?;
    core::check_case(&case.scene, &case.init).map_err(|e| PyCoreError(e, None).into())
}

/// Trace columns, in the order `trace_case` returns them.
const TRACE_COLUMNS: [&str; 15] = [
    "t",
    "x",
    "y",
    "phi",
    "vx",
    "vy",
    "omega",
    "f_n",
    "f_t",
    "area",
    "depth",
    "xi",
    "partner_phi",
    "partner_omega",
    "stick",
];

/// Runs the one impact of `row` (as [`run_case`]) and returns (its record as a tuple, trace
/// columns).
#[pyfunction]
#[pyo3(signature = (row, vertices, partner_vertices=None))]
fn trace_case<'py>(
    py: Python<'py>,
    row: [f64; core::CASE_COLUMNS.len()],
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    partner_vertices: Option<PyReadonlyArray2<'py, f64>>,
) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
    let case = read_case(row, (vertices, partner_vertices))?;
    let (rec, tr) = interruptible(py, false, |cancel| {
        core::simulate_with_trace_cancellable(&case.scene, &case.init, cancel)
    })?
    .map_err(|e| PyCoreError(e, Some(0)))?;
    let out = PyDict::new(py);
    let floats = [
        tr.t,
        tr.x,
        tr.y,
        tr.phi,
        tr.vx,
        tr.vy,
        tr.omega,
        tr.f_n,
        tr.f_t,
        tr.area,
        tr.depth,
        tr.xi,
        tr.partner_phi,
        tr.partner_omega,
    ];
    for (name, col) in TRACE_COLUMNS.iter().zip(floats) {
        out.set_item(name, PyArray1::from_vec(py, col))?;
    }
    out.set_item(TRACE_COLUMNS[14], PyArray1::from_vec(py, tr.stick))?;
    Ok((record_tuple(py, &rec)?, out))
}

/// Largest `dt_factor` each case of `columns` accepts: its integrator's stability bound for
/// that case's stiffness and damping (the column `dt_factor` itself is ignored). With
/// `explain`, also what sets each bound, in words.
#[pyfunction]
#[pyo3(signature = (columns, vertices, explain=false, partner_vertices=None))]
fn max_dt_factor_for<'py>(
    py: Python<'py>,
    columns: &Bound<'py, PyDict>,
    vertices: Option<PyReadonlyArray2<'py, f64>>,
    explain: bool,
    partner_vertices: Option<PyReadonlyArray2<'py, f64>>,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Option<Vec<String>>)> {
    let cases = read_cases(columns, (vertices, partner_vertices))?;
    let mut bounds = Vec::with_capacity(cases.len());
    let mut reasons = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        let err = |e| PyCoreError(e, Some(i));
        if explain {
            let (b, why) = core::max_dt_factor_reason(&case.scene).map_err(err)?;
            bounds.push(b);
            reasons.push(why);
        } else {
            bounds.push(core::max_dt_factor(&case.scene).map_err(err)?);
        }
    }
    Ok((PyArray1::from_vec(py, bounds), explain.then_some(reasons)))
}

/// Checks a shape given by its sweep columns: `n` (0: exact disc, >= 3: regular n-gon), its
/// circumradius `r` and its orientation `phi0_deg`.
#[pyfunction]
fn check_shape(n: f64, r: f64, phi0_deg: f64) -> PyResult<()> {
    core::shape_from_columns(n, r, None).map_err(|e| PyCoreError(e, None))?;
    core::check_orientation(phi0_deg).map_err(|e| PyCoreError(e, None).into())
}

/// Checks an impact angle (degrees from the plate): the engine's one rule for it.
#[pyfunction]
fn check_theta(theta_deg: f64) -> PyResult<()> {
    core::check_theta(theta_deg).map_err(|e| PyCoreError(e, None).into())
}

/// The Hertz law's damping ratio beta calibrated so that the head-on restitution is `cor`
/// (docs/model.md, section 14.3): what a translation into another code's damping needs.
#[pyfunction]
fn hertz_beta(cor: f64) -> PyResult<f64> {
    let beta = core::model::hertz::beta_for_cor(cor);
    if beta.is_nan() {
        let expected = format!("in [{}, 1]", core::model::hertz::MIN_COR);
        return Err(PyCoreError(core::Error::invalid("cor", cor, expected), None).into());
    }
    Ok(beta)
}

/// A convex polygon's vertices (counter-clockwise, any origin), checked by the engine, as
/// (the body-frame vertices about the centroid divided by the circumradius, the circumradius).
#[pyfunction]
fn convex_template<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, f64)> {
    let v = read_vertices(Some(vertices))?.unwrap_or_default();
    let shape = core::Shape::convex_polygon(&v).map_err(|e| PyCoreError(e, None))?;
    let r = shape.circumradius();
    let rows: Vec<Vec<f64>> = shape
        .vertices()
        .iter()
        .map(|p| vec![p.x / r, p.y / r])
        .collect();
    Ok((PyArray2::from_vec2(py, &rows)?, r))
}

/// The engine's choices as a dict: name -> tuple of public names in code order.
fn choices(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for (name, names) in core::CHOICES {
        out.set_item(name, PyTuple::new(py, names)?)?;
    }
    Ok(out)
}

/// The compiled engine of the `restitution` package.
#[pymodule]
mod _core {
    #[pymodule_export]
    use super::{
        check_case, check_cases, check_shape, check_theta, convex_template, hertz_beta,
        last_call_diagnostics, max_dt_factor_for, run_case, run_cases, trace_case,
    };

    #[pymodule_init]
    fn init(m: &pyo3::Bound<'_, pyo3::types::PyModule>) -> pyo3::PyResult<()> {
        use pyo3::types::{PyModuleMethods, PyTuple};
        let py = m.py();
        m.add("__version__", env!("CARGO_PKG_VERSION"))?;
        m.add(
            "CASE_COLUMNS",
            PyTuple::new(py, restitution_core::CASE_COLUMNS)?,
        )?;
        m.add(
            "RECORD_COLUMNS",
            PyTuple::new(py, restitution_core::RECORD_COLUMNS)?,
        )?;
        m.add("TRACE_COLUMNS", PyTuple::new(py, super::TRACE_COLUMNS)?)?;
        m.add("CHOICES", super::choices(py)?)?;
        Ok(())
    }
}

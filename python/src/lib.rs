//! `seasynth._seasynth`: the Python face of the seasynth library. The package's
//! `seasynth/__init__.py` wraps these in the documented API; this module converts
//! arguments, runs the library's `pipeline` functions with the interpreter released and
//! hands the results to numpy without copying them.

use std::path::PathBuf;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use numpy::ndarray::{ArrayView, Ix2, Ix3};
use numpy::{PyArray, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyMemoryError, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use seasynth::config::Params;
use seasynth::config::layers::{self, Assignment};
use seasynth::error::Error;
use seasynth::export::maps::{MapEncoding, MapKind};
use seasynth::export::options::ExportOptions;
use seasynth::field::Synthesis;
use seasynth::field::dynamics::Extras;
use seasynth::pipeline::{compute, sequence};

pyo3::create_exception!(
    _seasynth,
    ParamError,
    PyValueError,
    "A bad parameter or input: the message is the command line's one line."
);
pyo3::create_exception!(
    _seasynth,
    ResourceError,
    PyMemoryError,
    "A job refused before any allocation: its estimated memory exceeds what is available."
);

/// The Python exception of a library error: bad input is a `ParamError` (a
/// `ValueError`), a job too large for memory a `ResourceError` (a `MemoryError`), a
/// failed read or write an `OSError`.
fn py_err(e: anyhow::Error) -> PyErr {
    let text = format!("{e:#}");
    match e.downcast_ref::<Error>() {
        Some(Error::Memory { .. }) => ResourceError::new_err(text),
        Some(Error::Io { .. }) => PyOSError::new_err(text),
        Some(_) => ParamError::new_err(text),
        None => PyRuntimeError::new_err(text),
    }
}

/// Worker pools by thread count (`threads=None` uses the global pool of every core).
fn pool(threads: Option<usize>) -> PyResult<Option<Arc<rayon::ThreadPool>>> {
    static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());
    let Some(n) = threads else {
        return Ok(None);
    };
    if n == 0 {
        return Err(ParamError::new_err("threads must be ≥ 1 (got 0)"));
    }
    let mut pools = POOLS.lock().unwrap_or_else(|p| p.into_inner());
    if let Some((_, p)) = pools.iter().find(|(k, _)| *k == n) {
        return Ok(Some(p.clone()));
    }
    let p = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start worker threads: {e}")))?,
    );
    pools.push((n, p.clone()));
    Ok(Some(p))
}

/// Runs `work` on a worker thread (in the pool of `threads`) while this thread waits
/// with the interpreter released, checking for signals every 0.1 s: Ctrl-C raises
/// `KeyboardInterrupt` at once, and the result of the work in flight is dropped when it
/// ends (files are staged, so none is left partial).
fn run<T: Send + 'static>(
    py: Python<'_>,
    threads: Option<usize>,
    work: impl FnOnce() -> anyhow::Result<T> + Send + 'static,
) -> PyResult<T> {
    let pool = pool(threads)?;
    let (tx, rx) = mpsc::channel();
    std::thread::Builder::new()
        .name("seasynth".into())
        .spawn(move || {
            let result = match pool {
                Some(p) => p.install(work),
                None => work(),
            };
            // The receiver is gone when the caller was interrupted: nothing to do.
            tx.send(result).ok();
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    match wait(py, rx)? {
        (Some(result), _) => result.map_err(py_err),
        (None, _) => Err(PyRuntimeError::new_err("the computation failed (a panic)")),
    }
}

/// Waits for the next value on `rx` with the interpreter released, checking for signals
/// every 0.1 s (a `KeyboardInterrupt` is returned at once); `None` when the sender is
/// gone. Gives the receiver back.
fn wait<T: Send>(
    py: Python<'_>,
    mut rx: mpsc::Receiver<T>,
) -> PyResult<(Option<T>, mpsc::Receiver<T>)> {
    loop {
        let (got, back) = py.detach(move || (rx.recv_timeout(Duration::from_millis(100)), rx));
        rx = back;
        match got {
            Ok(value) => return Ok((Some(value), rx)),
            Err(RecvTimeoutError::Timeout) => py.check_signals()?,
            Err(RecvTimeoutError::Disconnected) => return Ok((None, rx)),
        }
    }
}

/// Resolved parameters: a preset with assignments applied and validated, as
/// `--preset` and `--set`/flags make them.
#[pyclass(module = "seasynth._seasynth", name = "Params", frozen)]
#[derive(Clone)]
struct PyParams {
    inner: Params,
}

/// `(key, value, origin)` assignments: `origin` is what error messages quote.
fn assignments(items: Vec<(String, String, String)>) -> Vec<Assignment> {
    items
        .into_iter()
        .map(|(key, value, origin)| Assignment { origin, key, value })
        .collect()
}

#[pymethods]
impl PyParams {
    /// The preset (a built-in name or a TOML file; default `li-tian`) with the
    /// assignments applied in order, then validated.
    #[new]
    #[pyo3(signature = (preset = None, items = Vec::new()))]
    fn new(preset: Option<&str>, items: Vec<(String, String, String)>) -> PyResult<Self> {
        layers::resolve(preset, &assignments(items))
            .map(|inner| Self { inner })
            .map_err(|e| py_err(e.into()))
    }

    /// These parameters with more assignments applied, then validated.
    fn apply(&self, items: Vec<(String, String, String)>) -> PyResult<Self> {
        layers::apply(self.inner.clone(), &assignments(items))
            .map(|inner| Self { inner })
            .map_err(|e| py_err(e.into()))
    }

    /// Parameters from the JSON of [`PyParams::to_json`] (a sidecar's `params`),
    /// validated as a preset is.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        seasynth::config::presets::parse_json("the parameters", text)
            .and_then(|p| layers::apply(p, &[]))
            .map(|inner| Self { inner })
            .map_err(|e| py_err(e.into()))
    }

    /// The resolved parameters as JSON, as sidecars record them.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The resolved parameters as a TOML preset file.
    fn to_toml(&self) -> PyResult<String> {
        toml::to_string(&self.inner).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The grid: (nx, ny, extent_x_m, extent_y_m, offset) where sample (i, j) sits at
    /// ((i + offset)·Lx/nx, (j + offset)·Ly/ny).
    fn grid(&self) -> (usize, usize, f64, f64, f64) {
        let s = self.inner.grid_spec();
        (
            s.nx,
            s.ny,
            s.extent_x_m,
            s.extent_y_m,
            self.inner.grid.sample_at.offset(),
        )
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
}

/// A synthesized field and the maps asked for, owned here: the numpy arrays are views
/// of this object's memory (their `base`), never copies.
#[pyclass(module = "seasynth._seasynth", name = "FieldCore", frozen)]
struct PyField {
    params: Params,
    synthesis: Synthesis,
    /// (λDx, λDy, h before the resampling), interleaved: a displacement EXR's (R, G, B)
    /// with `--up z`.
    displacement: Option<Vec<f32>>,
    /// Unit normals (x, y, z), interleaved.
    normal: Option<Vec<f32>>,
    jacobian: Option<Vec<f32>>,
    foam: Option<Vec<f32>>,
}

/// The maps `names` asks for (`displacement`, `normal`, `jacobian`, `foam`).
fn map_kinds(names: &[String]) -> PyResult<Vec<MapKind>> {
    names
        .iter()
        .map(|n| match n.as_str() {
            "displacement" | "disp" => Ok(MapKind::Displacement),
            "normal" => Ok(MapKind::Normal),
            "jacobian" => Ok(MapKind::Jacobian),
            "foam" => Ok(MapKind::Foam),
            other => Err(ParamError::new_err(format!(
                "maps must be among displacement, normal, jacobian, foam (got {other})"
            ))),
        })
        .collect()
}

/// The derived fields the maps `kinds` need.
fn extras_of(kinds: &[MapKind]) -> Extras {
    let encoded: Vec<(MapKind, MapEncoding)> =
        kinds.iter().map(|k| (*k, MapEncoding::Exr)).collect();
    seasynth::export::maps::extras_for(&encoded)
}

impl PyField {
    /// The field of `synthesis` with the maps `kinds` taken out of it; `foam`: the foam
    /// coverage already resolved (a sequence's), else this field's own.
    fn new(
        params: Params,
        synthesis: Synthesis,
        kinds: &[MapKind],
        foam: Option<Vec<f32>>,
    ) -> Self {
        let maps = compute::Maps::of(&params, &synthesis, kinds, foam);
        Self {
            params,
            synthesis,
            displacement: maps.displacement,
            normal: maps.normal,
            jacobian: maps.jacobian,
            foam: maps.foam,
        }
    }

    fn shape(&self) -> (usize, usize) {
        (self.synthesis.grid.spec.ny, self.synthesis.grid.spec.nx)
    }
}

/// A read-only numpy view of `data` (shape `dims`) kept alive by `owner`.
fn view2<'py>(
    owner: &Bound<'py, PyField>,
    data: &[f32],
    dims: (usize, usize),
) -> Bound<'py, PyArray<f32, Ix2>> {
    let v = ArrayView::from_shape(dims, data).expect("the data has the grid's length");
    // SAFETY: `owner` holds `data` (a frozen object's heap buffer, never moved or
    // changed while it lives), and the array keeps `owner` alive as its base.
    let a = unsafe { PyArray::borrow_from_array(&v, owner.clone().into_any()) };
    a.readwrite().make_nonwriteable();
    a
}

fn view3<'py>(
    owner: &Bound<'py, PyField>,
    data: &[f32],
    dims: (usize, usize, usize),
) -> Bound<'py, PyArray<f32, Ix3>> {
    let v = ArrayView::from_shape(dims, data).expect("the data has the grid's length");
    // SAFETY: as for `view2`.
    let a = unsafe { PyArray::borrow_from_array(&v, owner.clone().into_any()) };
    a.readwrite().make_nonwriteable();
    a
}

#[pymethods]
impl PyField {
    /// Heights in meters, (ny, nx) float32, row j at y_j.
    #[getter]
    fn height<'py>(slf: &Bound<'py, Self>) -> Bound<'py, PyArray<f32, Ix2>> {
        let me = slf.get();
        view2(slf, &me.synthesis.grid.data, me.shape())
    }

    /// (λDx, λDy, h) in meters, (ny, nx, 3), when asked for.
    #[getter]
    fn displacement<'py>(slf: &Bound<'py, Self>) -> Option<Bound<'py, PyArray<f32, Ix3>>> {
        let me = slf.get();
        let (ny, nx) = me.shape();
        me.displacement.as_ref().map(|d| view3(slf, d, (ny, nx, 3)))
    }

    /// Unit normals (x, y, z), (ny, nx, 3), when asked for.
    #[getter]
    fn normal<'py>(slf: &Bound<'py, Self>) -> Option<Bound<'py, PyArray<f32, Ix3>>> {
        let me = slf.get();
        let (ny, nx) = me.shape();
        me.normal.as_ref().map(|d| view3(slf, d, (ny, nx, 3)))
    }

    /// The Jacobian J of the choppy displacement, (ny, nx), when asked for.
    #[getter]
    fn jacobian<'py>(slf: &Bound<'py, Self>) -> Option<Bound<'py, PyArray<f32, Ix2>>> {
        let me = slf.get();
        me.jacobian.as_ref().map(|d| view2(slf, d, me.shape()))
    }

    /// Foam coverage 0..1, (ny, nx), when asked for.
    #[getter]
    fn foam<'py>(slf: &Bound<'py, Self>) -> Option<Bound<'py, PyArray<f32, Ix2>>> {
        let me = slf.get();
        me.foam.as_ref().map(|d| view2(slf, d, me.shape()))
    }

    /// The parameters of this field (its time included).
    #[getter]
    fn params(&self) -> PyParams {
        PyParams {
            inner: self.params.clone(),
        }
    }

    /// The JSON sidecar the command line writes beside this field's files (without
    /// their file list).
    fn sidecar_json(&self) -> PyResult<String> {
        compute::sidecar_json(&self.params, &self.synthesis).map_err(py_err)
    }

    /// Writes the field to every path (format by extension, maps by `NAME.KIND.ext`),
    /// each with its sidecar, as `seasynth generate -o PATH…` does; `flags`: export flags
    /// (`--exr-half`, `--up z`, …) as (flag, value) pairs.
    #[pyo3(signature = (paths, flags = Vec::new(), threads = None))]
    fn write(
        slf: &Bound<'_, Self>,
        paths: Vec<PathBuf>,
        flags: Vec<(String, String)>,
        threads: Option<usize>,
    ) -> PyResult<Vec<PathBuf>> {
        let me = slf.get();
        let params = me.params.clone();
        let computed = Synthesis {
            grid: me.synthesis.grid.clone(),
            info: me.synthesis.info.clone(),
            surface: Default::default(),
        };
        run(slf.py(), threads, move || {
            let options = ExportOptions::from_named_flags(&flags)?;
            let written = seasynth::pipeline::write::write_field(
                &params,
                &paths,
                &options,
                &Default::default(),
                Some(computed),
                false,
            )?;
            Ok(written.files)
        })
    }
}

/// The derived fields of the maps `kinds`; `resample` false: a choppy field keeps its
/// undisplaced heights and skips the resampling (a displacement map's heights).
fn extras_with(kinds: &[MapKind], resample: bool) -> Extras {
    let mut e = extras_of(kinds);
    e.maps_only = !resample;
    e
}

/// The field of `params` at its time, with the maps `maps`, computed on `threads`
/// worker threads (the same bits on any number).
#[pyfunction]
#[pyo3(signature = (params, maps = Vec::new(), threads = None, resample = true))]
fn generate(
    py: Python<'_>,
    params: &PyParams,
    maps: Vec<String>,
    threads: Option<usize>,
    resample: bool,
) -> PyResult<PyField> {
    let kinds = map_kinds(&maps)?;
    let params = params.inner.clone();
    run(py, threads, move || {
        let synthesis = compute::synthesize_checked(&params, extras_with(&kinds, resample))?;
        Ok(PyField::new(params, synthesis, &kinds, None))
    })
}

/// One sea prepared once for frames at any time: `generate` at each time, bit for bit,
/// without its preparation (the draws, and the binned pairs of a looping second-order
/// sea) every time.
#[pyclass(module = "seasynth._seasynth", name = "SeaCore", frozen)]
struct PySea {
    params: Params,
    kinds: Vec<MapKind>,
    threads: Option<usize>,
    prepared: Arc<compute::Prepared>,
}

#[pymethods]
impl PySea {
    #[new]
    #[pyo3(signature = (params, maps = Vec::new(), threads = None, resample = true))]
    fn new(
        py: Python<'_>,
        params: &PyParams,
        maps: Vec<String>,
        threads: Option<usize>,
        resample: bool,
    ) -> PyResult<Self> {
        let kinds = map_kinds(&maps)?;
        let p = params.inner.clone();
        let extras = extras_with(&kinds, resample);
        let prepared = run(py, threads, move || {
            Ok(Arc::new(compute::Prepared::new(&p, extras, true)?))
        })?;
        Ok(Self {
            params: params.inner.clone(),
            kinds,
            threads,
            prepared,
        })
    }

    /// The field at `time_s`.
    fn frame(&self, py: Python<'_>, time_s: f64) -> PyResult<PyField> {
        let (prepared, kinds) = (self.prepared.clone(), self.kinds.clone());
        let mut params = self.params.clone();
        params.time_s = time_s;
        run(py, self.threads, move || {
            let synthesis = prepared.frame(time_s)?;
            Ok(PyField::new(params, synthesis, &kinds, None))
        })
    }
}

/// The frames of a sequence, computed one ahead of the caller on a worker thread.
#[pyclass(module = "seasynth._seasynth", name = "Frames")]
struct PyFrames {
    rx: Mutex<Option<mpsc::Receiver<anyhow::Result<PyField>>>>,
}

#[pymethods]
impl PyFrames {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<Option<PyField>> {
        let taken = self.rx.lock().unwrap_or_else(|p| p.into_inner()).take();
        let Some(rx) = taken else {
            return Ok(None);
        };
        // On an interrupt the receiver is dropped, which stops the producer after its
        // frame.
        match wait(py, rx)? {
            (Some(Ok(frame)), rx) => {
                *self.rx.lock().unwrap_or_else(|p| p.into_inner()) = Some(rx);
                Ok(Some(frame))
            }
            (Some(Err(e)), _) => Err(py_err(e)),
            (None, _) => Ok(None),
        }
    }

    /// Stops the sequence: the frame in flight is dropped.
    fn close(&self) {
        self.rx.lock().unwrap_or_else(|p| p.into_inner()).take();
    }
}

/// Frames 0 … frames − 1 of the sequence of `params` (frame k at time + k/fps), with
/// the maps `maps`: `seasynth animate`'s frames, bit for bit.
#[pyfunction]
#[pyo3(signature = (params, frames, maps = Vec::new(), threads = None, resample = true))]
fn animate(
    params: &PyParams,
    frames: usize,
    maps: Vec<String>,
    threads: Option<usize>,
    resample: bool,
) -> PyResult<PyFrames> {
    let kinds = map_kinds(&maps)?;
    let params = params.inner.clone();
    let pool = pool(threads)?;
    // One frame ahead: the producer computes frame k + 1 while the caller holds k.
    let (tx, rx) = mpsc::sync_channel::<anyhow::Result<PyField>>(1);
    std::thread::Builder::new()
        .name("seasynth-frames".into())
        .spawn(move || {
            let produce = || {
                let foam = kinds.contains(&MapKind::Foam);
                let result = sequence::each_frame(
                    &params,
                    frames,
                    extras_with(&kinds, resample),
                    foam,
                    |f| {
                        let mut p = params.clone();
                        p.time_s = f.time_s;
                        let field = PyField::new(p, f.synthesis, &kinds, f.foam);
                        tx.send(Ok(field)).is_ok()
                    },
                );
                if let Err(e) = result {
                    tx.send(Err(e.into())).ok();
                }
            };
            match pool {
                Some(p) => p.install(produce),
                None => produce(),
            }
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    Ok(PyFrames {
        rx: Mutex::new(Some(rx)),
    })
}

/// Writes the frame sequence of `params` into `dir` as `seasynth animate` does: the
/// same files, `sequence.json`, and `resume`.
#[pyfunction]
#[pyo3(signature = (params, dir, frames, formats, flags = Vec::new(), start_frame = None, resume = false, threads = None))]
#[allow(clippy::too_many_arguments)]
fn write_sequence(
    py: Python<'_>,
    params: &PyParams,
    dir: PathBuf,
    frames: usize,
    formats: Vec<String>,
    flags: Vec<(String, String)>,
    start_frame: Option<usize>,
    resume: bool,
    threads: Option<usize>,
) -> PyResult<(usize, usize)> {
    let params = params.inner.clone();
    run(py, threads, move || {
        let done = sequence::write_sequence(&sequence::Sequence {
            params: &params,
            frames,
            formats: &formats,
            options: ExportOptions::from_named_flags(&flags)?,
            start_frame,
            dir: &dir,
            jobs: None,
            resume,
            quiet: true,
            force: false,
        })?;
        Ok((done.written, done.skipped))
    })
}

/// The `--json` report of `seasynth spectrum` at the frequencies `freqs` (Hz).
#[pyfunction]
fn spectrum_json(params: &PyParams, freqs: Vec<f64>) -> PyResult<String> {
    seasynth::pipeline::reports::spectrum_json(&params.inner, &freqs).map_err(py_err)
}

/// The `--json` report of `seasynth analyze` on a file.
#[pyfunction]
#[pyo3(signature = (path, options = Vec::new()))]
fn analyze_file(py: Python<'_>, path: PathBuf, options: Vec<(String, String)>) -> PyResult<String> {
    run(py, None, move || {
        seasynth::pipeline::reports::analyze_file_json(&path, &options)
    })
}

/// The `--json` report of `seasynth analyze` on heights in meters over an extent.
#[pyfunction]
fn analyze_array(
    py: Python<'_>,
    heights: PyReadonlyArray2<'_, f32>,
    extent_x_m: f64,
    extent_y_m: f64,
) -> PyResult<String> {
    let shape = heights.shape();
    let (ny, nx) = (shape[0], shape[1]);
    let data = heights
        .as_slice()
        .map_err(|_| ParamError::new_err("the array must be C-contiguous"))?
        .to_vec();
    run(py, None, move || {
        seasynth::pipeline::reports::analyze_array_json(data, nx, ny, extent_x_m, extent_y_m)
    })
}

/// The job list of a batch (`seasynth batch --plan --json`), each row with the job's
/// fully resolved parameters as `parameters` (absent for a bad job, whose `error` says
/// why).
#[pyfunction]
#[pyo3(signature = (preset, items, sweeps, sample, vary, design, design_seed, name))]
#[allow(clippy::too_many_arguments)]
fn plan_json(
    preset: Option<String>,
    items: Vec<(String, String, String)>,
    sweeps: Vec<String>,
    sample: Option<usize>,
    vary: Vec<String>,
    design: String,
    design_seed: Option<String>,
    name: Option<String>,
) -> PyResult<String> {
    use seasynth::pipeline::batch::list::{DesignArgs, ListArgs, job_list, plan_json};
    use seasynth::pipeline::batch::plan::Sweep;
    let sweeps = sweeps
        .iter()
        .map(|s| Sweep::parse(s))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| py_err(e.into()))?;
    let list = job_list(ListArgs {
        preset,
        base: assignments(items),
        sweeps,
        entries: Vec::new(),
        name,
        design: DesignArgs {
            sample,
            vary,
            design,
            design_seed,
        },
    })
    .map_err(|e| py_err(e.into()))?;
    let mut doc = plan_json(&list.jobs, &list.keys, |_| true);
    if let Some(rows) = doc.get_mut("rows").and_then(|r| r.as_array_mut()) {
        for (row, job) in rows.iter_mut().zip(&list.jobs) {
            if let (Some(obj), Ok(p)) = (row.as_object_mut(), &job.params) {
                let value =
                    serde_json::to_value(p).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
                obj.insert("parameters".into(), value);
            }
        }
    }
    Ok(doc.to_string())
}

/// Makes the allocator keep freed memory for reuse instead of returning it to the
/// system (glibc), as `seasynth animate` does: repeated fields of one size then reuse
/// their buffers instead of paying a page fault per 4 KiB. Kept until the process ends.
/// The work runs on a worker thread, whose own glibc arena would not keep large blocks,
/// so every thread is also given the main arena (`M_ARENA_MAX` = 1).
#[pyfunction]
fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets the allocator's tuning parameters (under its lock).
    unsafe {
        libc::mallopt(libc::M_ARENA_MAX, 1);
    }
    seasynth::pipeline::memory::keep_freed_memory();
}

/// The flag names accepted as keys and the preset key each stands for.
#[pyfunction]
fn flag_keys() -> Vec<(&'static str, &'static str)> {
    layers::FLAG_KEYS.to_vec()
}

/// The built-in presets' names.
#[pyfunction]
fn presets() -> Vec<&'static str> {
    seasynth::config::presets::BUILTIN
        .iter()
        .map(|(n, _)| *n)
        .collect()
}

#[pymodule]
fn _seasynth(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyParams>()?;
    m.add_class::<PyField>()?;
    m.add_class::<PyFrames>()?;
    m.add_class::<PySea>()?;
    m.add_function(wrap_pyfunction!(generate, m)?)?;
    m.add_function(wrap_pyfunction!(animate, m)?)?;
    m.add_function(wrap_pyfunction!(write_sequence, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum_json, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_file, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_array, m)?)?;
    m.add_function(wrap_pyfunction!(plan_json, m)?)?;
    m.add_function(wrap_pyfunction!(flag_keys, m)?)?;
    m.add_function(wrap_pyfunction!(keep_freed_memory, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add("ParamError", m.py().get_type::<ParamError>())?;
    m.add("ResourceError", m.py().get_type::<ResourceError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

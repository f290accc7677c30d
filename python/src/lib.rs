//! `hatchery._hatchery`: the native half of the Python package (issue 26). It wraps the same
//! [`hatchery_nodes::Session`] the command line and the editor run, so one graph renders the
//! same from all three. The Python half (`python/hatchery/`) turns numpy arrays into the flat
//! buffers taken here and wraps results; this module does no array reshaping of its own.

mod batch;
mod catalogue;
mod errors;
mod graph;
mod inputs;
mod params;

use numpy::PyUntypedArrayMethods;
use pyo3::prelude::*;

/// The GPU the process renders on: opened once, shared by every Graph (a device per graph would
/// cost its start-up and memory for each). Errors: no adapter (the message says how to get one).
fn shared_gpu() -> Result<hatchery_gpu::GpuContext, String> {
    static GPU: std::sync::OnceLock<Result<hatchery_gpu::GpuContext, String>> =
        std::sync::OnceLock::new();
    GPU.get_or_init(|| hatchery_gpu::GpuContext::new().map_err(|e| e.to_string()))
        .clone()
}

/// The adapter graphs render on, in words ("llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, cpu)").
/// Raises RenderError when no GPU adapter can be opened.
#[pyfunction]
fn adapter(py: Python<'_>) -> PyResult<String> {
    py.detach(shared_gpu)
        .map(|g| g.describe())
        .map_err(errors::RenderError::new_err)
}

/// PNG bytes of `rgba` (a flat (h, w, 4) uint8 buffer): what `Picture._repr_png_` shows.
/// Raises ValueError when the size does not match.
#[pyfunction]
fn png_bytes(
    py: Python<'_>,
    rgba: numpy::PyReadonlyArray1<'_, u8>,
    width: u32,
    height: u32,
) -> PyResult<Py<pyo3::types::PyBytes>> {
    let pixels = rgba
        .as_slice()
        .map_err(|_| pyo3::exceptions::PyValueError::new_err("the pixels are not contiguous"))?
        .to_vec();
    let image = image::RgbaImage::from_raw(width, height, pixels).ok_or_else(|| {
        pyo3::exceptions::PyValueError::new_err(format!(
            "{} bytes are not a {width}×{height} RGBA picture",
            rgba.len()
        ))
    })?;
    let mut png = Vec::new();
    py.detach(|| image.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png))
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    Ok(pyo3::types::PyBytes::new(py, &png).unbind())
}

#[pymodule]
fn _hatchery(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("HatcheryError", py.get_type::<errors::HatcheryError>())?;
    m.add("GraphError", py.get_type::<errors::GraphError>())?;
    m.add("InputError", py.get_type::<errors::InputError>())?;
    m.add("ParamError", py.get_type::<errors::ParamError>())?;
    m.add("RenderError", py.get_type::<errors::RenderError>())?;
    m.add("JobError", py.get_type::<errors::JobError>())?;
    m.add_function(wrap_pyfunction!(batch::batch_items, m)?)?;
    m.add_function(wrap_pyfunction!(batch::batch_run, m)?)?;
    m.add_function(wrap_pyfunction!(batch::batch_merge, m)?)?;
    m.add_class::<graph::Graph>()?;
    m.add_function(wrap_pyfunction!(catalogue::nodes, m)?)?;
    m.add_function(wrap_pyfunction!(adapter, m)?)?;
    m.add_function(wrap_pyfunction!(png_bytes, m)?)?;
    m.add("FORMAT_VERSION", hatchery_graph::FORMAT_VERSION)?;
    Ok(())
}

//! An EXR's layers as Python data: `irsig_raster` reads the file (the one reader of the
//! project's images), and each layer's samples go into a `bytes` object once, which NumPy
//! then views without a copy (`numpy.frombuffer`). The angles of a view's pixel centres
//! come from the tracer's camera (`irsig_tracer::Camera`), the model that aimed the rays.

use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::errors::to_py;

/// One layer: its name, its unit and its samples as native-endian `f32` bytes, row-major
/// from the top.
type PyLayer<'py> = (String, String, Bound<'py, PyBytes>);

/// What `read_exr` gives: width, height, the layers, the provenance (the `comments`
/// attribute) and the run (`irsig.run`), the last two `None` where the file has none.
type PyRaster<'py> = (
    usize,
    usize,
    Vec<PyLayer<'py>>,
    Option<String>,
    Option<String>,
);

/// Reads an EXR's bytes (`name` for messages) into its layers.
///
/// Raises `IrsigError` for a file that is not an image irsig reads.
#[pyfunction]
pub(crate) fn read_exr<'py>(py: Python<'py>, name: &str, bytes: &[u8]) -> PyResult<PyRaster<'py>> {
    let raster = py
        .detach(|| irsig_raster::read_exr(bytes))
        .map_err(|e| to_py(&miette::miette!("{name}: {e}")))?;
    let layers = raster
        .layers
        .iter()
        .map(|layer| {
            let len = layer.data.len() * size_of::<f32>();
            let data = PyBytes::new_with(py, len, |out| {
                for (chunk, v) in out.chunks_exact_mut(size_of::<f32>()).zip(&layer.data) {
                    chunk.copy_from_slice(&v.to_ne_bytes());
                }
                Ok(())
            })?;
            Ok((layer.name.clone(), layer.unit.clone(), data))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let run = raster.part.map(|p| p.run);
    Ok((raster.width, raster.height, layers, raster.comments, run))
}

/// The signed angles from the optical axis, degrees, of the pixel centres of `view`'s
/// columns (positive to the right) and rows (positive upward), each measured in the image's
/// middle row or column along the direction the tracer's camera gives the pixel.
pub(crate) fn angles_deg(view: &irsig_model::View) -> miette::Result<(Vec<f64>, Vec<f64>)> {
    let camera = irsig_tracer::Camera::from_view(view).map_err(|e| miette::miette!("{e}"))?;
    let [columns, rows] = camera.pixels;
    let (mid_x, mid_y) = (f64::from(columns) / 2.0, f64::from(rows) / 2.0);
    let axis = camera.direction_at(mid_x, mid_y);
    let off_axis = |x: f64, y: f64, signed: f64| {
        let d = camera.direction_at(x, y);
        let cos = (d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2]).clamp(-1.0, 1.0);
        cos.acos().to_degrees().copysign(signed)
    };
    let x = (0..columns)
        .map(|c| {
            let x = f64::from(c) + 0.5;
            off_axis(x, mid_y, x - mid_x)
        })
        .collect();
    let y = (0..rows)
        .map(|r| {
            let y = f64::from(r) + 0.5;
            off_axis(mid_x, y, mid_y - y)
        })
        .collect();
    Ok((x, y))
}

//! 3-D reconstruction (paper §II, eq. 1).
//!
//! With parallel optical axes and the baseline along the image rows, a point
//! seen at pixel `(x, y)` of the reference view with disparity `D` (pixels)
//! lies at `Z = f·b / (D·p)`, `X = x·b / D`, `Y = y·b / D`, where `b` is the
//! baseline, `f` the focal length and `p` the pixel pitch; `x`, `y` are
//! measured from the principal point. With the focal length given in pixels
//! (`f/p`), `Z = f_px·b / D`. The paper's rig: f = 8 mm, b = 8 cm.

/// The camera pair's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Focal length in pixels (`f / p`).
    pub focal_px: f64,
    /// Baseline `b` in metres.
    pub baseline_m: f64,
    /// Principal point, pixels.
    pub cx: f64,
    /// Principal point, pixels.
    pub cy: f64,
}

impl Camera {
    /// A camera with its principal point at the centre of a `width × height`
    /// image.
    pub fn centred(focal_px: f64, baseline_m: f64, width: usize, height: usize) -> Self {
        Camera {
            focal_px,
            baseline_m,
            cx: (width as f64 - 1.0) / 2.0,
            cy: (height as f64 - 1.0) / 2.0,
        }
    }
}

/// Eq. 1: depth `Z = f·b / D` in metres for a disparity `D > 0` in pixels.
pub fn depth(d: f64, cam: &Camera) -> Option<f64> {
    (d > 0.0).then(|| cam.focal_px * cam.baseline_m / d)
}

/// Eq. 1: the point `(X, Y, Z)` in metres (camera frame, `Y` down) of pixel
/// `(x, y)` with disparity `d > 0`.
pub fn point(x: f64, y: f64, d: f64, cam: &Camera) -> Option<[f64; 3]> {
    let z = depth(d, cam)?;
    Some([(x - cam.cx) * cam.baseline_m / d, (y - cam.cy) * cam.baseline_m / d, z])
}

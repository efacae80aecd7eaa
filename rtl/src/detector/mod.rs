//! The declivity detector of one camera (paper §II, eq. 2–3): the pixel window, the self-adaptive threshold, the extrema tracker, the divider of eq. 3 and the detector that joins them.

pub(crate) mod pixel_window;
pub mod adaptive_threshold;
pub(crate) mod declivity_tracker;
pub(crate) mod position_divider;
pub mod declivity_detector;

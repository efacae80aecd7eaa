//! After the matcher: the row check, the interpolator (paper §IV), the vertical median and the depth stage (eq. 1).

pub mod row_check;
pub(crate) mod neighbour_window;
pub mod interpolator;
pub mod vertical_median;
pub mod depth_stage;

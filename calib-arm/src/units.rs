//! Degrees in the files, radians in the model: conversions that keep boxes sound.
//!
//! A box read in degrees is turned into a box in radians by multiplying both bounds by an
//! enclosure of `π/180` in interval arithmetic (outward rounded), so the radian box contains every
//! angle the degree box does; certified radian boxes go back to degrees the same way.

use calib_core::Interval;

/// An enclosure of `π/180`.
pub fn rad_per_deg() -> Interval {
    Interval::PI / Interval::point(180.0)
}

/// The radian box containing the degree box `deg`.
pub fn deg_to_rad(deg: Interval) -> Interval {
    deg * rad_per_deg()
}

/// The degree box containing the radian box `rad`.
pub fn rad_to_deg(rad: Interval) -> Interval {
    rad / rad_per_deg()
}

/// A radian value in degrees, to the nearest double (for display and for points that are
/// re-certified in radians anyway).
pub fn to_deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// A degree value in radians, to the nearest double (for simulation and least squares, never for
/// a certified box).
pub fn to_rad(deg: f64) -> f64 {
    deg.to_radians()
}

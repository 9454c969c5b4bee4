//! From measured configurations and error bounds to the measurement boxes `M_k` of one leg.

use crate::geometry::rodrigues_box;
use crate::simulate::{Configuration, Uncertainty};
use calib_core::Interval;

/// The box `M_k = (P, q, L)` of leg `leg` (0-based) in every configuration: position ± `pos`,
/// Rodrigues box of (axis ± `axis`) × (angle ± `angle_deg`), reading ± `len`; all outward rounded.
pub fn leg_boxes(configs: &[Configuration], u: &Uncertainty, leg: usize) -> Vec<[Interval; 7]> {
    configs
        .iter()
        .map(|c| {
            let axis = c.pose.axis.map(|v| Interval::mid_rad(v, u.axis));
            let q = rodrigues_box(&axis, Interval::mid_rad(c.pose.angle_deg, u.angle_deg));
            let p = c.pose.p.map(|v| Interval::mid_rad(v, u.pos));
            [
                p[0],
                p[1],
                p[2],
                q[0],
                q[1],
                q[2],
                Interval::mid_rad(c.lengths[leg], u.len),
            ]
        })
        .collect()
}

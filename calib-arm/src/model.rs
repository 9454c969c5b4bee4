//! The serial-arm residual: the tracked point predicted by the kinematic parameters minus the
//! point the tracker measured, three rows sharing one configuration's joint readings.
//!
//! `p = T_base · A_1(q_1) ⋯ A_N(q_N) · t` with
//! `T_base = Trans(base_x, base_y, base_z) · Rz(base_rz) · Ry(base_ry) · Rx(base_rx)` (tracker frame
//! to robot base), `A_i(q) = Rz(theta_i + q) · Tz(d_i) · Tx(a_i) · Rx(alpha_i) · Ry(beta_i)`
//! (standard Denavit–Hartenberg plus Hayati's `beta` for joints whose next axis is parallel) and
//! `t = (tool_x, tool_y, tool_z)` in the flange frame.
//!
//! Parameters, `5N + 9` of them: `theta_i, d_i, a_i, alpha_i, beta_i` per joint (base to flange),
//! then `base_x, base_y, base_z, base_rx, base_ry, base_rz`, then `tool_x, tool_y, tool_z`.
//! Measurements, `N + 3`: the joint readings `q_1..q_N`, then the tracked point `px, py, pz`.
//! Lengths in mm; **angles in radians** inside the model (the files are in degrees: the crate
//! converts boxes outward, see [`crate::units`]), so that no decimal approximation of `π/180`
//! enters the residual.
//!
//! The point is carried from the tool through each joint to the tracker frame, one rotation at a
//! time, so the evaluators never form a matrix product. The residual is written for 7 joints
//! ([`arm7_point`], an ordinary `#[interval_model]` function: a [`calib_core::VectorModel`] with
//! three rows); an arm of fewer joints is padded with identity joints
//! ([`crate::certification::padded_index`]). One model keeps the build short: measured, dropping
//! the 3- to 6-joint models saved ~6 s of the library's build and ~20 s of its test binary's
//! (which instantiated the kernel for a second model).

/// Writes the residual of an `N`-joint arm under `#[interval_model]`: parameter and measurement
/// indices are spelled out as literals (the attribute needs constant indices), joints listed from
/// the flange to the base (the order in which they act on the tool point). With `two_frames`,
/// also the same arm's residual for rows from two tracker frames (the joints spelled once).
macro_rules! serial_arm_model {
    (
        $(#[$doc:meta])*
        $name:ident,
        nx = $nx:literal,
        nm = $nm:literal,
        tool = $tool:tt,
        joints_from_flange = $joints:tt,
        base = $base:tt,
        point = $point:tt,
        two_frames = (
            $(#[$doc2:meta])*
            $name2:ident,
            nx = $nx2:literal,
            nm = $nm2:literal,
            earlier_frame = $earlier:tt
        )
    ) => {
        serial_arm_model!(
            $(#[$doc])* $name, nx = $nx, nm = $nm, tool = $tool, joints_from_flange = $joints,
            base = $base, point = $point
        );
        serial_arm_model!(
            $(#[$doc2])* $name2, nx = $nx2, nm = $nm2, tool = $tool, joints_from_flange = $joints,
            base = $base, point = $point, earlier_frame = $earlier
        );
    };
    (
        $(#[$doc:meta])*
        $name:ident,
        nx = $nx:literal,
        nm = $nm:literal,
        tool = [$tx:literal, $ty:literal, $tz:literal],
        joints_from_flange = [$(($t:literal, $d:literal, $a:literal, $al:literal, $b:literal, $q:literal)),+ $(,)?],
        base = [$bx:literal, $by:literal, $bz:literal, $rx:literal, $ry:literal, $rz:literal],
        point = [$px:literal, $py:literal, $pz:literal]
        $(, earlier_frame = (
            flag = $f:literal,
            base = [$ebx:literal, $eby:literal, $ebz:literal, $erx:literal, $ery:literal, $erz:literal],
            tool = [$etx:literal, $ety:literal, $etz:literal]
        ))?
    ) => {
        $(#[$doc])*
        #[calib_core::interval_model(curvature)]
        pub fn $name<S: calib_core::Scalar>(x: &[S; $nx], m: &[S; $nm]) -> [S; 3] {
            let v = [x[$tx], x[$ty], x[$tz]];
            let base = [x[$bx], x[$by], x[$bz], x[$rx], x[$ry], x[$rz]];
            $(
                // A row of the earlier frame (flag 1) takes that frame's base and tool: with the
                // flag a point 0 or 1, `a (1 - f) + b f` is `a` or `b` (in intervals, `a` or `b`
                // widened outward by the product's rounding, `0 · b` exactly 0).
                let (now, then) = (1.0 - m[$f], m[$f]);
                let [vx, vy, vz] = v;
                let v = [vx * now + x[$etx] * then, vy * now + x[$ety] * then, vz * now + x[$etz] * then];
                let [b0, b1, b2, b3, b4, b5] = base;
                let base = [
                    b0 * now + x[$ebx] * then,
                    b1 * now + x[$eby] * then,
                    b2 * now + x[$ebz] * then,
                    b3 * now + x[$erx] * then,
                    b4 * now + x[$ery] * then,
                    b5 * now + x[$erz] * then,
                ];
            )?
            $(
                // A_i(q) v = Rz(theta + q) Tz(d) Tx(a) Rx(alpha) Ry(beta) v
                let v = {
                    let [vx, vy, vz] = v;
                    let (cb, sb) = (x[$b].cos(), x[$b].sin());
                    let (ux, uz) = (vx * cb + vz * sb, vz * cb - vx * sb);
                    let (ca, sa) = (x[$al].cos(), x[$al].sin());
                    let (wy, wz) = (vy * ca - uz * sa, vy * sa + uz * ca);
                    let (px, pz) = (ux + x[$a], wz + x[$d]);
                    let th = x[$t] + m[$q];
                    let (ct, st) = (th.cos(), th.sin());
                    [px * ct - wy * st, px * st + wy * ct, pz]
                };
            )+
            let [vx, vy, vz] = v;
            let [base_x, base_y, base_z, base_rx, base_ry, base_rz] = base;
            // Rx(base_rx), Ry(base_ry), Rz(base_rz), then the translation.
            let (cx, sx) = (base_rx.cos(), base_rx.sin());
            let (y1, z1) = (vy * cx - vz * sx, vy * sx + vz * cx);
            let (cy, sy) = (base_ry.cos(), base_ry.sin());
            let (x2, z2) = (vx * cy + z1 * sy, z1 * cy - vx * sy);
            let (cz, sz) = (base_rz.cos(), base_rz.sin());
            let (x3, y3) = (x2 * cz - y1 * sz, x2 * sz + y1 * cz);
            [
                base_x + x3 - m[$px],
                base_y + y3 - m[$py],
                base_z + z2 - m[$pz],
            ]
        }
    };
}

serial_arm_model!(
    /// The tracked point of a 7-joint arm minus its measurement (see the module documentation).
    arm7_point,
    nx = 44,
    nm = 10,
    tool = [41, 42, 43],
    joints_from_flange = [
        (30, 31, 32, 33, 34, 6),
        (25, 26, 27, 28, 29, 5),
        (20, 21, 22, 23, 24, 4),
        (15, 16, 17, 18, 19, 3),
        (10, 11, 12, 13, 14, 2),
        (5, 6, 7, 8, 9, 1),
        (0, 1, 2, 3, 4, 0)
    ],
    base = [35, 36, 37, 38, 39, 40],
    point = [7, 8, 9],
    two_frames = (
        /// [`arm7_point`] for rows from two tracker frames: parameters 44–49 are the earlier
        /// frame's base and 50–52 its tool point, and measured quantity 10 says which frame a row
        /// is in (0: this one, 1: the earlier one, always a point). See [`crate::carry`].
        arm7_point_two_frames,
        nx = 53,
        nm = 11,
        earlier_frame = (flag = 10, base = [44, 45, 46, 47, 48, 49], tool = [50, 51, 52])
    )
);

/// The tracked point `p(x, q)` of an arm with `q.len()` joints (3 to 7) in floating point, from
/// the same residual (`f(x, (q, 0)) = p`): parameters in model order and units (radians), joint
/// readings in radians. `None` for another joint count or mismatched lengths.
///
/// An arm of fewer than 7 joints goes through [`Arm7Point`] padded with identity joints (every
/// parameter and reading 0: `cos 0 = 1` and `sin 0 = 0` exactly, so the padding changes no bit of
/// the result), as everywhere else in the crate ([`crate::certification::padded_index`]).
pub fn tracked_point(x: &[f64], q: &[f64]) -> Option<[f64; 3]> {
    use crate::certification::{padded_index, MAX_JOINTS, NM, NX};
    use calib_core::VectorModel;
    let joints = q.len();
    if !(3..=MAX_JOINTS).contains(&joints) || x.len() != crate::params::count(joints) {
        return None;
    }
    let mut padded = [0.0; NX];
    for (&p, &v) in padded_index(joints).iter().zip(x) {
        padded[p] = v;
    }
    let mut m = [0.0; NM];
    m[..joints].copy_from_slice(q);
    Some(Arm7Point.residuals(&padded, &m))
}

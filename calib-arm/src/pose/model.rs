//! The six-row serial-arm residual: the tracked point, as [`crate::Arm7Point`], and the
//! orientation of the measured frame (a tracker's 6-DoF probe, e.g. Leica's T-Mac), three rows
//! sharing one configuration's joint readings.
//!
//! Parameters, `5N + 12` of them: the point model's `5N + 9` (joints, base, tool point), then the
//! tool frame's rotation `tool_rx, tool_ry, tool_rz` on the flange,
//! `R_tool = Rz(tool_rz) Ry(tool_ry) Rx(tool_rx)` (the base's convention). Measured quantities,
//! `N + 6`: the joint readings, the tracked point, then the measured orientation as intrinsic
//! Euler angles `XYZ`, `R_meas = Rx(a) Ry(b) Rz(c)` (radians inside the model).
//!
//! The model's orientation is `R = R_base A_1(q_1) ⋯ A_N(q_N) R_tool` (the rotation parts of
//! [`crate::model`]'s transforms). It is carried as a unit quaternion, left-multiplied from the
//! tool to the base by the quaternion of each elementary rotation (`(cos φ/2, sin φ/2 e)` for a
//! rotation by `φ` about the axis `e`); so is the measurement's. The orientation rows are the
//! vector part of `q_meas* ⊗ q_model`, times 1000: zero **exactly** when the two rotations are
//! equal (the vector part of a unit quaternion vanishes only at `±1`, the identity), with no
//! spurious zero at half a turn as the skew part of `R_measᵀ R` would have; for a small
//! difference by the rotation vector `θ` (radians, measured frame) the rows are `500 θ`, so that
//! one milliradian weighs about as much as half a millimetre in the position rows (what the real
//! UR10's data leave of each, see `calib-arm/examples/orientation_study.rs`). The factor is an
//! integer: it changes no zero of the residual, only the rows' scale in least squares.

/// Writes the six-row residual of a 7-joint arm (literal indices, as
/// [`crate::model`]'s generator: joints listed from the flange to the base).
macro_rules! serial_arm_pose_model {
    (
        $(#[$doc:meta])*
        $name:ident,
        nx = $nx:literal,
        nm = $nm:literal,
        tool = [$tx:literal, $ty:literal, $tz:literal],
        tool_rotation = [$trx:literal, $try:literal, $trz:literal],
        joints_from_flange = [$(($t:literal, $d:literal, $a:literal, $al:literal, $b:literal, $q:literal)),+ $(,)?],
        base = [$bx:literal, $by:literal, $bz:literal, $rx:literal, $ry:literal, $rz:literal],
        point = [$px:literal, $py:literal, $pz:literal],
        euler_xyz = [$ea:literal, $eb:literal, $ec:literal]
    ) => {
        $(#[$doc])*
        #[calib_core::interval_model(curvature)]
        pub fn $name<S: calib_core::Scalar>(x: &[S; $nx], m: &[S; $nm]) -> [S; 6] {
            // The tool frame's rotation Rz Ry Rx as a quaternion (w, i, j, k).
            let (cx, sx) = ((x[$trx] * 0.5).cos(), (x[$trx] * 0.5).sin());
            let (cy, sy) = ((x[$try] * 0.5).cos(), (x[$try] * 0.5).sin());
            let (cz, sz) = ((x[$trz] * 0.5).cos(), (x[$trz] * 0.5).sin());
            // qy(ry) qx(rx) = (cy cx, cy sx, sy cx, -sy sx), then qz(rz) on the left.
            let (qw, qi, qj, qk) = (cy * cx, cy * sx, sy * cx, -(sy * sx));
            let (qw, qi, qj, qk) = (cz * qw - sz * qk, cz * qi - sz * qj, cz * qj + sz * qi, cz * qk + sz * qw);
            let v = [x[$tx], x[$ty], x[$tz]];
            $(
                // A_i(q) v = Rz(theta + q) Tz(d) Tx(a) Rx(alpha) Ry(beta) v
                let (cb, sb) = (x[$b].cos(), x[$b].sin());
                let (ca, sa) = (x[$al].cos(), x[$al].sin());
                let th = x[$t] + m[$q];
                let (ct, st) = (th.cos(), th.sin());
                let v = {
                    let [vx, vy, vz] = v;
                    let (ux, uz) = (vx * cb + vz * sb, vz * cb - vx * sb);
                    let (wy, wz) = (vy * ca - uz * sa, vy * sa + uz * ca);
                    let (px, pz) = (ux + x[$a], wz + x[$d]);
                    [px * ct - wy * st, px * st + wy * ct, pz]
                };
                // q <- qz(theta + q) qx(alpha) qy(beta) q, one left product at a time.
                let (c, s) = ((x[$b] * 0.5).cos(), (x[$b] * 0.5).sin());
                let (qw, qi, qj, qk) = (c * qw - s * qj, c * qi + s * qk, c * qj + s * qw, c * qk - s * qi);
                let (c, s) = ((x[$al] * 0.5).cos(), (x[$al] * 0.5).sin());
                let (qw, qi, qj, qk) = (c * qw - s * qi, c * qi + s * qw, c * qj - s * qk, c * qk + s * qj);
                let (c, s) = ((th * 0.5).cos(), (th * 0.5).sin());
                let (qw, qi, qj, qk) = (c * qw - s * qk, c * qi - s * qj, c * qj + s * qi, c * qk + s * qw);
            )+
            let [vx, vy, vz] = v;
            // Rx(base_rx), Ry(base_ry), Rz(base_rz), then the translation.
            let (cx, sx) = (x[$rx].cos(), x[$rx].sin());
            let (y1, z1) = (vy * cx - vz * sx, vy * sx + vz * cx);
            let (cy, sy) = (x[$ry].cos(), x[$ry].sin());
            let (x2, z2) = (vx * cy + z1 * sy, z1 * cy - vx * sy);
            let (cz, sz) = (x[$rz].cos(), x[$rz].sin());
            let (x3, y3) = (x2 * cz - y1 * sz, x2 * sz + y1 * cz);
            let (c, s) = ((x[$rx] * 0.5).cos(), (x[$rx] * 0.5).sin());
            let (qw, qi, qj, qk) = (c * qw - s * qi, c * qi + s * qw, c * qj - s * qk, c * qk + s * qj);
            let (c, s) = ((x[$ry] * 0.5).cos(), (x[$ry] * 0.5).sin());
            let (qw, qi, qj, qk) = (c * qw - s * qj, c * qi + s * qk, c * qj + s * qw, c * qk - s * qi);
            let (c, s) = ((x[$rz] * 0.5).cos(), (x[$rz] * 0.5).sin());
            let (qw, qi, qj, qk) = (c * qw - s * qk, c * qi - s * qj, c * qj + s * qi, c * qk + s * qw);
            // The measurement: qx(a) qy(b) qz(c), right products.
            let (ca, sa) = ((m[$ea] * 0.5).cos(), (m[$ea] * 0.5).sin());
            let (cb, sb) = ((m[$eb] * 0.5).cos(), (m[$eb] * 0.5).sin());
            let (cc, sc) = ((m[$ec] * 0.5).cos(), (m[$ec] * 0.5).sin());
            // qx(a) qy(b) = (ca cb, sa cb, ca sb, sa sb), then qz(c) on the right.
            let (mw, mi, mj, mk) = (ca * cb, sa * cb, ca * sb, sa * sb);
            let (mw, mi, mj, mk) = (mw * cc - mk * sc, mi * cc + mj * sc, mj * cc - mi * sc, mw * sc + mk * cc);
            [
                x[$bx] + x3 - m[$px],
                x[$by] + y3 - m[$py],
                x[$bz] + z2 - m[$pz],
                (mw * qi - mi * qw - mj * qk + mk * qj) * 1000.0,
                (mw * qj + mi * qk - mj * qw - mk * qi) * 1000.0,
                (mw * qk - mi * qj + mj * qi - mk * qw) * 1000.0,
            ]
        }
    };
}

serial_arm_pose_model!(
    /// The tracked point and the measured frame's orientation of a 7-joint arm minus their
    /// measurements (see the module documentation).
    arm7_pose,
    nx = 47,
    nm = 13,
    tool = [41, 42, 43],
    tool_rotation = [44, 45, 46],
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
    euler_xyz = [10, 11, 12]
);

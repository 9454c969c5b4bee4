//! The tests of `calib_arm::vendor`.

mod tests {
    use calib_arm::vendor::*;

    use nalgebra::{Isometry3, Translation3, UnitQuaternion};
    use rand::{Rng, SeedableRng};

    /// A random rigid transform: translation within ±`t` mm, any rotation.
    fn random_frame(rng: &mut impl Rng, t: f64) -> Frame {
        let mut v = || rng.random_range(-1.0..1.0);
        Isometry3::from_parts(
            Translation3::new(t * v(), t * v(), t * v()),
            UnitQuaternion::from_euler_angles(3.0 * v(), 1.5 * v(), 3.0 * v()),
        )
    }

    #[test]
    fn random_chains_become_arms_with_the_same_flange_and_back() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(3);
        let radii = ImportRadii {
            angle_deg: 0.1,
            length_mm: 1.0,
        };
        for trial in 0..200 {
            let n = 3 + trial % 5;
            let mut origins: Vec<Frame> = (0..n).map(|_| random_frame(&mut rng, 500.0)).collect();
            // Every other chain: a first joint turning about the base's z, nearly parallel axes.
            if trial % 2 == 0 {
                origins[0] = rz(rng.random_range(-3.0..3.0)) * trans(0.0, 0.0, 120.0);
                origins[2] = trans(-600.0, 3.0, 40.0) * rx(1e-3) * ry(-2e-3);
            }
            let arm = chain_to_arm(&origins, radii).expect("an arm");
            let back = arm_to_chain(&arm).expect("a chain");
            let base = base_frame(&arm.base);
            for _ in 0..5 {
                let q: Vec<f64> = (0..n).map(|_| rng.random_range(-3.2..3.2)).collect();
                let want = chain_flange(&origins, &q);
                let got = arm_flange(&arm, &q);
                let again = base * chain_flange(&back, &q);
                for f in [got, again] {
                    let dt = (f.translation.vector - want.translation.vector).norm();
                    let dr = f.rotation.angle_to(&want.rotation);
                    assert!(dt < 1e-9 && dr < 1e-12, "trial {trial}: {dt} mm, {dr} rad");
                }
                // The model's residual computes the same point.
                let units = calib_arm::params::names(n);
                let x: Vec<f64> = arm
                    .nominal()
                    .iter()
                    .zip(&units)
                    .map(|(v, (_, u))| match u {
                        calib_arm::params::Unit::Deg => v.to_radians(),
                        calib_arm::params::Unit::Mm => *v,
                    })
                    .collect();
                let p = calib_arm::model::tracked_point(&x, &q).expect("a point");
                let want_p = arm_point(&arm, &q);
                assert!((0..3).all(|c| (p[c] - want_p[c]).abs() < 1e-9));
            }
        }
    }

    #[test]
    fn a_chain_with_a_non_finite_number_is_no_arm() {
        let radii = ImportRadii {
            angle_deg: 0.1,
            length_mm: 1.0,
        };
        let good = [trans(0.0, 0.0, 120.0), trans(300.0, 0.0, 0.0), rx(0.5)];
        assert!(chain_to_arm(&good, radii).is_ok());
        // Wherever the NaN or the infinity sits (the first origin goes to the base, the others
        // into the links), it is an error, never an arm to write.
        for k in 0..3 {
            for bad in [f64::NAN, f64::INFINITY] {
                let mut origins = good;
                origins[k] *= trans(bad, 0.0, 0.0);
                let e = chain_to_arm(&origins, radii).unwrap_err().to_string();
                assert!(
                    e.contains("non-finite") || e.contains("split"),
                    "{k} {bad}: {e}"
                );
            }
        }
    }

    #[test]
    fn the_import_agreement_is_at_rounding_level_and_sees_a_changed_parameter() {
        use calib_arm::vendor::agreement;
        let mut rng = rand::rngs::StdRng::seed_from_u64(8);
        let radii = ImportRadii {
            angle_deg: 0.1,
            length_mm: 1.0,
        };
        for _ in 0..20 {
            let origins: Vec<Frame> = (0..6).map(|_| random_frame(&mut rng, 500.0)).collect();
            let mut arm = chain_to_arm(&origins, radii).expect("an arm");
            let (distance, angle, _) = agreement(&origins, &arm, 64);
            assert!(
                distance < 1e-9 && angle < 1e-12,
                "{distance} mm, {angle} rad"
            );
            // Half a millimetre on one length: seen, at least mostly, somewhere.
            arm.joints[2].nominal[2] += 0.5;
            let (distance, _, at) = agreement(&origins, &arm, 64);
            assert!((0.45..=0.5 + 1e-9).contains(&distance), "{distance} mm");
            assert_eq!(at.len(), 6);
            // A NaN is the worst of all.
            arm.joints[0].nominal[1] = f64::NAN;
            assert_eq!(agreement(&origins, &arm, 8).0, f64::INFINITY);
        }
    }
}

mod ur10 {
    use calib_arm::vendor::*;

    #[test]
    fn the_ur10_yaml_imports_as_ur_s_published_denavit_hartenberg_parameters() {
        let text = include_str!("../../tests/data/ur10_default_kinematics.yaml");
        let k = ur_yaml::parse(std::path::Path::new("ur10.yaml"), text).expect("UR10");
        let radii = ImportRadii {
            angle_deg: 0.1,
            length_mm: 1.0,
        };
        let arm = chain_to_arm(&k.origins, radii).expect("an arm");
        let d = [127.3, 0.0, 0.0, 163.941, 115.7, 92.2];
        let a = [0.0, -612.0, -572.3, 0.0, 0.0, 0.0];
        let alpha = [90.0, 0.0, 0.0, 90.0, -90.0, 0.0];
        for (i, j) in arm.joints.iter().enumerate() {
            let [theta, dj, aj, al, beta] = j.nominal;
            let close = |x: f64, y: f64| (x - y).abs() < 1e-6;
            assert!(
                close(theta, 0.0) && close(dj, d[i]) && close(aj, a[i]) && close(al, alpha[i]),
                "joint {}: {:?}",
                i + 1,
                j.nominal
            );
            assert!(close(beta, 0.0));
        }
        // The identifiable set of the built-in arm: 18 joint parameters (+ base and tool).
        let free = arm
            .joints
            .iter()
            .flat_map(|j| j.radius)
            .filter(|r| *r > 0.0)
            .count();
        assert_eq!(free, 18);
        assert_eq!(arm.base, [0.0; 6]);
    }
}

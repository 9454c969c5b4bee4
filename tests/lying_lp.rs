//! The certificate does not depend on the LP engine: an engine that returns wrong multipliers,
//! wrong primal points and false infeasibility claims cannot make the kernel lose a solution or
//! claim emptiness — the safe bounds and the Farkas check catch every lie, in `certify` and in
//! `hull`, which shaves and discards boxes with the same engine. A lying engine that also asks to
//! skip LPs whose bound an earlier (lying) optimum attains cannot either.

use calib_core::{certify_with, hull_with, Interval, Settings, Status, Workspace};
use calib_core::{LpBackend, LpStatus, Polyhedron};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};

/// A deliberately wrong LP engine driven by a small deterministic generator.
struct LyingLp {
    state: u64,
    /// Whether it asks the contraction to skip LPs whose bound an earlier (lying) optimum
    /// attains: its primal points often sit exactly on a face, so skips happen.
    skips: bool,
}

impl LyingLp {
    fn next(&mut self) -> f64 {
        self.state = self
            .state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.state >> 11) as f64 / (1u64 << 53) as f64
    }
}

impl LpBackend for LyingLp {
    fn name(&self) -> &'static str {
        "liar"
    }

    fn skips_attained_bounds(&self, _dim: usize) -> bool {
        self.skips
    }

    fn minimize(
        &mut self,
        p: &Polyhedron,
        _c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus {
        let mode = self.next();
        for d in dual.iter_mut() {
            // Wild multipliers: negative, huge, NaN, or plausible.
            let r = self.next();
            *d = if r < 0.1 {
                f64::NAN
            } else if r < 0.3 {
                -r * 1e3
            } else {
                r * 10f64.powi((r * 12.0) as i32 - 6)
            };
        }
        for (j, x) in primal.iter_mut().enumerate() {
            let r = self.next();
            *x = if r < 0.3 {
                p.lo()[j]
            } else if r < 0.5 {
                p.hi()[j]
            } else if r < 0.75 {
                p.lo()[j] + (p.hi()[j] - p.lo()[j]) * self.next()
            } else {
                p.lo()[j] + (p.hi()[j] - p.lo()[j]) * self.next() * 3.0
            };
        }
        if mode < 0.4 {
            LpStatus::Infeasible
        } else if mode < 0.7 {
            LpStatus::Optimal
        } else {
            LpStatus::Failed
        }
    }
}

#[test]
fn a_lying_lp_engine_cannot_break_the_certificate() {
    let truth = builtin_hexapod();
    let mut skipped = 0;
    for seed in 0..6u64 {
        let sim = simulate(&truth, 21, seed, Uncertainty::PAPER, 1.0, 0.1);
        let leg = (seed % 6) as usize;
        let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
        let x0 = sim.nominal[leg].params().map(|v| Interval::mid_rad(v, 0.1));
        let skips = seed % 2 == 0;
        let liar = LyingLp {
            state: seed + 1,
            skips,
        };
        let mut ws = Workspace::with_backend(Box::new(liar));
        let r = certify_with(&GoughLeg, &x0, &boxes, &Settings::default(), &mut ws);
        assert_ne!(
            r.status,
            Status::Empty,
            "seed {seed}: a lie was accepted as a proof"
        );
        let t = truth[leg].params();
        for j in 0..7 {
            assert!(
                r.outer[j].contains(t[j]),
                "seed {seed}: the truth was cut from parameter {j}"
            );
            assert!(r.outer[j].is_subset_of(x0[j]));
        }
        assert!(r.lp_failures > 0, "the lies were noticed");
        if skips {
            skipped += ws.lp_skipped;
        } else {
            assert_eq!(
                ws.lp_skipped, 0,
                "seed {seed}: an engine that does not skip"
            );
        }
    }
    assert!(
        skipped > 0,
        "lying optima on faces made the contraction skip LPs"
    );
}

#[test]
fn a_lying_lp_engine_cannot_break_the_hull() {
    let truth = builtin_hexapod();
    for seed in 0..3u64 {
        let sim = simulate(&truth, 21, seed, Uncertainty::PAPER, 1.0, 0.1);
        let leg = (2 * seed % 6) as usize;
        let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
        let x0 = sim.nominal[leg].params().map(|v| Interval::mid_rad(v, 0.1));
        let state = std::sync::atomic::AtomicU64::new(seed + 1);
        let liar = || -> Box<dyn LpBackend> {
            let s = state.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            Box::new(LyingLp {
                state: s,
                skips: s % 2 == 0,
            })
        };
        let settings = Settings::default().with_hull_budget(600, None);
        let h = hull_with(&GoughLeg, &x0, &boxes, &settings, &liar);
        assert_ne!(h.status, Status::Empty, "seed {seed}: a lie became a proof");
        let t = truth[leg].params();
        for j in 0..7 {
            assert!(
                h.outer[j].contains(t[j]),
                "seed {seed}: the truth was cut from parameter {j}"
            );
            assert!(h.outer[j].is_subset_of(x0[j]));
        }
    }
}

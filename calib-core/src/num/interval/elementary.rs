//! Elementary functions: `sqrt`, `abs`, `min`, `max`, `sin`, `cos`, `tan`.
//!
//! `sin`, `cos` and `tan` find the extrema (or poles) inside the argument with a conservative test:
//! the index `k` of each critical point `c + k*period` is enclosed by interval arithmetic with an
//! enclosure of pi, and a critical point is assumed present whenever the enclosure admits an integer.
//! Otherwise the function is monotone on the argument and the bounds come from the end points,
//! widened by two ulps (see the module documentation of [`crate::num::interval`]).

use super::round::{down, up};
use super::Interval;
use std::cell::Cell;
use std::thread::LocalKey;

/// Beyond this magnitude the critical-point test is not attempted and `[-1, 1]` is returned.
const LARGE_ARGUMENT: f64 = 1.0e15;

/// Entries of each thread's table of recent `sin` / `cos` results (a power of two).
const MEMO_SLOTS: usize = 256;

/// A direct-mapped table of results by the argument's bits: `(bits of lo, bits of hi, result)`.
type MemoTable = [Cell<(u64, u64, Interval)>; MEMO_SLOTS];

/// The empty argument and its result: every slot starts as a true entry.
const EMPTY_ENTRY: (u64, u64, Interval) = (
    Interval::EMPTY.lo.to_bits(),
    Interval::EMPTY.hi.to_bits(),
    Interval::EMPTY,
);

thread_local! {
    // A residual evaluates the trigonometry of its measured angles, which stay the same over
    // every Newton step and every box of a sweep: the measurement box's angle in the evaluation
    // over the box, its midpoint at the relaxation's corners. The results are pure functions of
    // the argument's bits, so a remembered one is the very interval a new evaluation would give.
    static SIN_MEMO: MemoTable = const { [const { Cell::new(EMPTY_ENTRY) }; MEMO_SLOTS] };
    static COS_MEMO: MemoTable = const { [const { Cell::new(EMPTY_ENTRY) }; MEMO_SLOTS] };
}

/// `f(x)`, from `table` when its slot for `x` holds `x`'s result (the same bits `f` gives).
#[inline]
fn memoised(
    table: &'static LocalKey<MemoTable>,
    x: Interval,
    f: impl FnOnce(Interval) -> Interval,
) -> Interval {
    let key = (x.lo.to_bits(), x.hi.to_bits());
    let hash = (key.0 ^ key.1.rotate_left(29)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    let slot = (hash >> (64 - MEMO_SLOTS.trailing_zeros())) as usize;
    if let Ok((lo, hi, value)) = table.try_with(|t| t[slot].get()) {
        if (lo, hi) == key {
            return value;
        }
    }
    let value = f(x);
    // (During the thread's teardown the table is gone: the value is then not remembered.)
    let _ = table.try_with(|t| t[slot].set((key.0, key.1, value)));
    value
}

fn down2(x: f64) -> f64 {
    down(down(x))
}

fn up2(x: f64) -> f64 {
    up(up(x))
}

impl Interval {
    /// The square root `{sqrt(x) : x >= 0}`; the negative part of the argument is outside the
    /// domain and dropped, so `[-4, 4].sqrt() = [0, 2]` and `[-2, -1].sqrt()` is empty.
    #[inline]
    pub fn sqrt(self) -> Interval {
        if self.is_empty() || self.hi < 0.0 {
            return Interval::EMPTY;
        }
        let lo = self.lo.max(0.0);
        let slo = if lo == 0.0 {
            0.0
        } else {
            down(lo.sqrt()).max(0.0)
        };
        let shi = if self.hi == 0.0 {
            0.0
        } else {
            up(self.hi.sqrt())
        };
        Interval::from_bounds_unchecked(slo, shi)
    }

    /// The absolute value `{|x|}` (exact).
    #[inline]
    pub fn abs(self) -> Interval {
        if self.is_empty() {
            Interval::EMPTY
        } else if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            -self
        } else {
            Interval::from_bounds_unchecked(0.0, (-self.lo).max(self.hi))
        }
    }

    /// The pointwise minimum `{min(x, y)}` (exact).
    #[inline]
    pub fn min(self, other: Interval) -> Interval {
        if self.is_empty() || other.is_empty() {
            return Interval::EMPTY;
        }
        Interval::from_bounds_unchecked(self.lo.min(other.lo), self.hi.min(other.hi))
    }

    /// The pointwise maximum `{max(x, y)}` (exact).
    #[inline]
    pub fn max(self, other: Interval) -> Interval {
        if self.is_empty() || other.is_empty() {
            return Interval::EMPTY;
        }
        Interval::from_bounds_unchecked(self.lo.max(other.lo), self.hi.max(other.hi))
    }

    /// The sine `{sin(x)}`.
    pub fn sin(self) -> Interval {
        // Maxima at pi/2 + 2k pi, minima at -pi/2 + 2k pi.
        memoised(&SIN_MEMO, self, |x| {
            x.periodic_unit_range(0.5, -0.5, f64::sin)
        })
    }

    /// The cosine `{cos(x)}`.
    pub fn cos(self) -> Interval {
        // Maxima at 2k pi, minima at pi + 2k pi.
        memoised(&COS_MEMO, self, |x| {
            x.periodic_unit_range(0.0, 1.0, f64::cos)
        })
    }

    /// The tangent `{tan(x) : x != pi/2 + k pi}`; `ENTIRE` when the argument may contain a pole.
    pub fn tan(self) -> Interval {
        if self.is_empty() {
            return Interval::EMPTY;
        }
        if !self.is_bounded() || self.mag() > LARGE_ARGUMENT {
            return Interval::ENTIRE;
        }
        // Poles at pi/2 + k pi.
        if may_contain_point(self, 0.5, 1.0) {
            return Interval::ENTIRE;
        }
        let lo = down2(self.lo.tan());
        let hi = up2(self.hi.tan());
        if lo > hi {
            // The libm results straddle a pole that the conservative test could not see (impossible
            // with a sound test, kept as a guard against a wrong libm): give up soundly.
            return Interval::ENTIRE;
        }
        Interval::from_bounds_unchecked(lo, hi)
    }

    /// Range of a 2pi-periodic function with values in [-1, 1], maxima at `max_at * pi + 2k pi`
    /// and minima at `min_at * pi + 2k pi`, monotone between them.
    fn periodic_unit_range(self, max_at: f64, min_at: f64, f: fn(f64) -> f64) -> Interval {
        if self.is_empty() {
            return Interval::EMPTY;
        }
        let unit = Interval::from_bounds_unchecked(-1.0, 1.0);
        if !self.is_bounded() || self.mag() > LARGE_ARGUMENT {
            return unit;
        }
        // A point argument (a measured value at a box's corner, a certified point) needs one
        // evaluation, and both extremum tests share `x / pi`: the same bounds for less work.
        let fa = f(self.lo);
        let fb = if self.hi == self.lo { fa } else { f(self.hi) };
        let mut lo = down2(fa.min(fb)).max(-1.0);
        let mut hi = up2(fa.max(fb)).min(1.0);
        let turns = self / Interval::PI;
        if may_contain_turn(turns, max_at, 2.0) {
            hi = 1.0;
        }
        if may_contain_turn(turns, min_at, 2.0) {
            lo = -1.0;
        }
        Interval::from_bounds_unchecked(lo, hi)
    }
}

/// Whether `x` may contain a point `(offset + k * period) * pi` for an integer `k` (conservative:
/// `true` whenever it cannot be excluded).
fn may_contain_point(x: Interval, offset: f64, period: f64) -> bool {
    may_contain_turn(x / Interval::PI, offset, period)
}

/// [`may_contain_point`] from `turns`, an enclosure of `x / pi`.
fn may_contain_turn(turns: Interval, offset: f64, period: f64) -> bool {
    // k in (x / pi - offset) / period, enclosed with outward rounding.
    let k = (turns - Interval::point(offset)) / Interval::point(period);
    k.sup().floor() >= k.inf().ceil()
}

#[cfg(test)]
mod tests {
    use super::Interval;

    /// A remembered `sin`/`cos` is bit for bit the fresh evaluation, whatever the table held
    /// before (repeated arguments, slots shared by several arguments, signed zeros, points,
    /// wide and unbounded arguments), on this thread and on another.
    #[test]
    fn remembered_sin_and_cos_are_the_fresh_evaluations() {
        fn fresh(x: Interval) -> (Interval, Interval) {
            (
                x.periodic_unit_range(0.5, -0.5, f64::sin),
                x.periodic_unit_range(0.0, 1.0, f64::cos),
            )
        }
        let mut args = vec![
            Interval::ZERO,
            Interval::new(-0.0, 0.0),
            Interval::new(-0.0, -0.0),
            Interval::ENTIRE,
            Interval::EMPTY,
            Interval::new(1.0, 2.0),
            Interval::new(0.0, 100.0),
        ];
        let mut seed = 11u64;
        for _ in 0..2000 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let a = ((seed >> 11) as f64 / (1u64 << 53) as f64) * 20.0 - 10.0;
            let w = ((seed >> 3) & 0xff) as f64 * 1e-3;
            args.push(if seed & 1 == 0 {
                Interval::point(a)
            } else {
                Interval::new(a, a + w)
            });
        }
        fn check(args: &[Interval]) {
            for _ in 0..3 {
                for &x in args {
                    let (s, c) = fresh(x);
                    let (ms, mc) = (x.sin(), x.cos());
                    assert!(
                        ms.inf().to_bits() == s.inf().to_bits()
                            && ms.sup().to_bits() == s.sup().to_bits()
                            && mc.inf().to_bits() == c.inf().to_bits()
                            && mc.sup().to_bits() == c.sup().to_bits(),
                        "{x:?}: remembered {ms:?} {mc:?}, fresh {s:?} {c:?}"
                    );
                }
            }
        }
        check(&args);
        let other: Vec<Interval> = args.iter().rev().copied().collect();
        std::thread::spawn(move || check(&other))
            .join()
            .expect("the other thread's check");
    }
}

//! The curvature of a model: second and third derivatives of a
//! [`VectorModel`](crate::VectorModel)'s rows, the [`Curvature`] trait
//! `#[interval_model(curvature)]` implements, and the evaluators its generated code calls
//! (forward-mode second-order [`Jet2`]s of [`Jet`]s over intervals). The second-order emptiness
//! proof that uses them is `proof::second_order`.

use crate::{Interval, Jet, Jet2};

/// The most symbols (parameters and measured quantities of nonzero width, per configuration) the
/// second-order evaluators take: the width of their [`Jet2`]s.
pub const MAX_CURVATURE_SYMBOLS: usize = 40;

/// The distinct second derivatives of [`MAX_CURVATURE_SYMBOLS`] symbols.
const PAIRS: usize = MAX_CURVATURE_SYMBOLS * (MAX_CURVATURE_SYMBOLS + 1) / 2;

/// The scalar of [`second_derivatives`] and [`third_derivatives_along`]: second-order forward
/// derivatives (symmetric, [`Jet2`]) of a directional derivative over intervals. One type for
/// both, so that a model's evaluator is compiled once for them (a second type for the second
/// derivatives alone made a fresh `cargo test --workspace` measurably longer). A jet of jets
/// (`Jet<Jet<Jet<Interval, 1>, 40>, 40>`) gives the same enclosures from twice the entries, and
/// was slower (`benches/README.md`, "Timings moved from code comments").
pub type Third = Jet2<Jet<Interval, 1>, MAX_CURVATURE_SYMBOLS, PAIRS>;

/// Stack of the threads that evaluate a model over [`Third`] (a value is 27 KB, and a residual's
/// evaluator keeps hundreds of them alive; only the pages used are committed).
const STACK_BYTES: usize = 512 << 20;

/// Second and third derivatives of a [`VectorModel`](crate::VectorModel)'s rows, for second-order
/// emptiness proofs. `#[interval_model(curvature)]` implements it for a residual; `symbols` index
/// `z = (x, M)`: `j < NX` is parameter `j`, `NX + i` measured quantity `i`. Both methods return
/// `NR` blocks of `S × S` enclosures (`S = symbols.len()`, row-major), `None` when `S >
/// MAX_CURVATURE_SYMBOLS`.
pub trait Curvature<const NX: usize, const NM: usize, const NR: usize>: Sync {
    /// Whether a first derivative of some row depends on `symbol` (index as in `symbols`).
    /// `false` promises that every second and third derivative involving it is 0: the bounds
    /// leave it out of the symbols (its first-order term is exact). `true` by default;
    /// `#[interval_model(curvature)]` reads it off the expression graph.
    fn curved(&self, _symbol: usize) -> bool {
        true
    }

    /// Enclosures of `∂²f_r/∂z_a∂z_b` at the point `(x, m)`.
    fn second_derivatives(
        &self,
        x: &[f64; NX],
        m: &[f64; NM],
        symbols: &[usize],
    ) -> Option<Vec<Interval>>;

    /// Enclosures of `Σ_c ∂³f_r/∂z_a∂z_b∂z_c (ξ) (z_c − z0_c)` for every `ξ` and `z` in the boxes
    /// `(x, m)`, with `z0 = (x0, m0)`.
    fn third_derivatives_along(
        &self,
        x: &[Interval; NX],
        m: &[Interval; NM],
        x0: &[f64; NX],
        m0: &[f64; NM],
        symbols: &[usize],
    ) -> Option<Vec<Interval>>;
}

/// [`Curvature::second_derivatives`] of the rows `values` (a residual's evaluator over [`Third`],
/// at the point, whose directional part stays 0), evaluated on a thread of its own with a large
/// stack.
pub fn second_derivatives<const NX: usize, const NM: usize, const NR: usize>(
    values: fn(&[Third; NX], &[Third; NM]) -> [Third; NR],
    x: &[f64; NX],
    m: &[f64; NM],
    symbols: &[usize],
) -> Option<Vec<Interval>> {
    if symbols.len() > MAX_CURVATURE_SYMBOLS {
        return None;
    }
    let input = |v: f64, k: usize| -> Third {
        let v = Jet::constant(Interval::point(v));
        match symbols.iter().position(|&s| s == k) {
            Some(a) => Jet2::variable(v, a),
            None => Jet2::constant(v),
        }
    };
    on_large_stack(|| {
        let xs: [Third; NX] = core::array::from_fn(|j| input(x[j], j));
        let ms: [Third; NM] = core::array::from_fn(|i| input(m[i], NX + i));
        let f = values(&xs, &ms);
        let n = symbols.len();
        let mut out = Vec::with_capacity(NR * n * n);
        for row in &f {
            for a in 0..n {
                out.extend((0..n).map(|b| row.second(a, b).value));
            }
        }
        out
    })
}

/// [`Curvature::third_derivatives_along`] of the rows `values` (a residual's evaluator over
/// [`Third`]), evaluated on a thread of its own with a large stack: each symbol enters as its box
/// with the directional seed `z − z0` (an interval), so the directional derivative of the second
/// derivatives encloses `Σ_c T_abc(ξ) (z_c − z0_c)`.
pub fn third_derivatives_along<const NX: usize, const NM: usize, const NR: usize>(
    values: fn(&[Third; NX], &[Third; NM]) -> [Third; NR],
    x: &[Interval; NX],
    m: &[Interval; NM],
    x0: &[f64; NX],
    m0: &[f64; NM],
    symbols: &[usize],
) -> Option<Vec<Interval>> {
    if symbols.len() > MAX_CURVATURE_SYMBOLS {
        return None;
    }
    let input = |v: Interval, centre: f64, k: usize| -> Third {
        match symbols.iter().position(|&s| s == k) {
            Some(a) => {
                let along = Jet {
                    value: v,
                    grad: [v - Interval::point(centre)],
                };
                Jet2::variable(along, a)
            }
            None => Jet2::constant(Jet::constant(v)),
        }
    };
    on_large_stack(|| {
        let xs: [Third; NX] = core::array::from_fn(|j| input(x[j], x0[j], j));
        let ms: [Third; NM] = core::array::from_fn(|i| input(m[i], m0[i], NX + i));
        let f = values(&xs, &ms);
        let n = symbols.len();
        let mut out = Vec::with_capacity(NR * n * n);
        for row in &f {
            for a in 0..n {
                out.extend((0..n).map(|b| row.second(a, b).grad[0]));
            }
        }
        out
    })
}

std::thread_local! {
    /// Whether this thread was started by [`on_large_stack`].
    static LARGE_STACK: core::cell::Cell<bool> = const { core::cell::Cell::new(false) };
}

/// Runs `f` on a scoped thread with a [`STACK_BYTES`] stack, or at once on a thread that already
/// has one (`None` if the thread cannot start or `f` panics).
fn on_large_stack<T: Send>(f: impl FnOnce() -> T + Send) -> Option<T> {
    if LARGE_STACK.with(|l| l.get()) {
        return Some(f());
    }
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(STACK_BYTES)
            .spawn_scoped(s, || {
                LARGE_STACK.with(|l| l.set(true));
                f()
            })
            .ok()?
            .join()
            .ok()
    })
}

/// `f` of every item, in order, computed by as many threads with [`STACK_BYTES`] stacks as the
/// machine runs in parallel, each taking a contiguous share (so the result does not depend on
/// the threads). `None` if a thread cannot start or panics.
pub(crate) fn on_large_stacks<I: Sync, T: Send>(
    items: &[I],
    f: impl Fn(&I) -> T + Sync,
) -> Option<Vec<T>> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, items.len().max(1));
    let share = items.len().div_ceil(threads).max(1);
    std::thread::scope(|s| {
        let handles: Vec<_> = items
            .chunks(share)
            .map(|chunk| {
                let f = &f;
                std::thread::Builder::new()
                    .stack_size(STACK_BYTES)
                    .spawn_scoped(s, move || {
                        LARGE_STACK.with(|l| l.set(true));
                        chunk.iter().map(f).collect::<Vec<T>>()
                    })
                    .ok()
            })
            .collect();
        let mut out = Vec::with_capacity(items.len());
        for h in handles {
            out.extend(h?.join().ok()?);
        }
        Some(out)
    })
}

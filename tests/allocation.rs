//! After a warm-up, one contraction performs zero heap allocations (a counting global allocator
//! proves it).
//!
//! The allocator counts per thread: the test harness's own thread allocates while a test runs
//! (its bookkeeping, late on a loaded machine), and those allocations are not the contraction's.
//! A contraction that started a thread would still be counted: spawning allocates on the caller.

use calib_core::{contract, Interval, Settings, Workspace};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Allocations made by this thread so far (const-initialised and without a destructor, so
    /// reading it from the allocator never allocates).
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Counts one allocation of the calling thread (none during the thread's teardown).
fn count() {
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

/// The calling thread's allocations so far.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

// SAFETY: forwards to the system allocator unchanged and only counts calls.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_contraction_after_warm_up_allocates_nothing() {
    let sim = simulate(&builtin_hexapod(), 21, 5, Uncertainty::PAPER, 1.0, 0.1);
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 0);
    let x0 = sim.nominal[0].params().map(|v| Interval::mid_rad(v, 0.1));
    let settings = Settings::default();
    let mut ws = Workspace::new(&settings);
    let warm = contract(&GoughLeg, &x0, &boxes, &settings, &mut ws);
    assert!(warm.result.is_ok());
    let before = allocations();
    let again = contract(&GoughLeg, &x0, &boxes, &settings, &mut ws);
    let after = allocations();
    assert_eq!(after - before, 0, "a warmed-up contraction allocated");
    assert_eq!(again, warm);
    // A different box of the same problem reuses the buffers too.
    let sub: [Interval; 7] = core::array::from_fn(|j| Interval::new(x0[j].inf(), x0[j].mid()));
    let before = allocations();
    let _ = contract(&GoughLeg, &sub, &boxes, &settings, &mut ws);
    assert_eq!(allocations() - before, 0);
}

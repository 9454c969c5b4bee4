//! The tests of `calib_pipeline::html`.

use calib_core::Interval;
use calib_pipeline::html::*;

#[test]
fn sha256_matches_known_digests() {
    assert_eq!(
        sha256_hex(b""),
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
    );
    assert_eq!(
        sha256_hex(b"abc"),
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
    );
}

#[test]
fn printed_bounds_keep_their_meaning() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    for _ in 0..20_000 {
        let lo: f64 = rng.random_range(-100.0..100.0);
        let hi = lo + rng.random_range(0.0..0.01) * rng.random_range(0.0..1.0f64).powi(4);
        let v = Interval::new(lo, hi);
        let parse = |s: &str| -> (f64, f64) {
            let inner = s.trim_start_matches('[').trim_end_matches(']');
            let (a, b) = inner.split_once(", ").unwrap();
            (a.parse().unwrap(), b.parse().unwrap())
        };
        let (a, b) = parse(&outward(v));
        assert!(a <= lo && hi <= b, "{v:?} printed {}", outward(v));
        let text = inward(v);
        let (a, b) = parse(&text);
        assert!(lo <= a && b <= hi && a <= b, "{v:?} printed {text}");
    }
    assert_eq!(outward(Interval::new(1.0, 2.0)), "[1.00000, 2.00000]");
    assert_eq!(rounded(0.123456, true), "0.12345");
    assert_eq!(rounded(0.123451, false), "0.12346");
    assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
}

//! Compile-fail tests: every unsupported construct in an `#[interval_model]` body or signature gives
//! one clear error pointing at the offending tokens (snapshots in `tests/ui/*.stderr`).

#[test]
fn unsupported_syntax_is_a_clear_compile_error() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}

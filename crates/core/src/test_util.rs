//! Helpers shared by the unit tests of agesim-core.

/// Asserts `|actual − expected| ≤ tol`, printing both values and the difference when not.
#[track_caller]
pub fn close(actual: f32, expected: f32, tol: f32) {
    assert!(
        (actual - expected).abs() <= tol,
        "expected {expected}, got {actual} (difference {}, tolerance {tol})",
        actual - expected
    );
}

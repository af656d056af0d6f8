//! Branch-free `exp` and `ln` in plain f32 arithmetic for the micro-relief hot loops.
//!
//! Why not `f32::exp`/`f32::ln`: those call the platform's libm, which neither vectorises
//! nor promises the same last bit on every machine (docs/models.md §1 "Determinism" asks for
//! byte-identical maps everywhere). These use only `+ − × ÷`, integer bit tricks and
//! comparisons, so the autovectoriser turns them into SIMD code and every instruction set
//! (SSE2 baseline or AVX2) computes the same IEEE results. No fused multiply-add is used.
//! Relative error below 3e-7 (exp) and 2e-7 (ln) on the ranges stated (checked in the tests).

/// 1.5·2²³: adding it rounds an f32 of magnitude < 2²² to an integer, without `round()`
/// (which would be a libm call on the SSE2 baseline).
const ROUND_MAGIC: f32 = 12_582_912.0;

/// e^x for x in [−87, 88]; inputs outside are clamped (so e^−1000 = e^−87 ≈ 1.6e−38, not 0).
#[inline(always)]
pub fn exp(x: f32) -> f32 {
    let x = x.clamp(-87.0, 88.0);
    // x = n·ln2 + r, |r| ≤ ln2/2; ln2 split in a high part exact in f32 and a low part.
    let t = x * std::f32::consts::LOG2_E + ROUND_MAGIC;
    let n = t - ROUND_MAGIC;
    let r = (x - n * 0.693_145_75) - n * 1.428_606_8e-6;
    // Taylor to degree 6: |r|⁷/7! < 1.3e−7 relative.
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0))))));
    let ni = (t.to_bits() as i32).wrapping_sub(ROUND_MAGIC.to_bits() as i32);
    p * f32::from_bits(((ni + 127) as u32) << 23)
}

/// ln(x) for x in [f32::MIN_POSITIVE, f32::MAX]; 0 and negative inputs give a large negative
/// finite number (callers only pass x ≥ 1).
#[inline(always)]
pub fn ln(x: f32) -> f32 {
    let bits = x.max(f32::MIN_POSITIVE).to_bits();
    let mut e = ((bits >> 23) as i32 - 127) as f32;
    let mut m = f32::from_bits((bits & 0x007F_FFFF) | 0x3F80_0000); // [1, 2)
    // Move m to [√½, √2) so that s below stays small.
    let big = m > std::f32::consts::SQRT_2;
    m = if big { m * 0.5 } else { m };
    e = if big { e + 1.0 } else { e };
    // ln m = 2·atanh(s), s = (m − 1)/(m + 1), |s| ≤ 0.1716.
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let lnm = 2.0 * s * (1.0 + s2 * (1.0 / 3.0 + s2 * (1.0 / 5.0 + s2 * (1.0 / 7.0 + s2 / 9.0))));
    e * std::f32::consts::LN_2 + lnm
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::worst_relative_error;

    #[test]
    fn exp_matches_f64_to_3e7() {
        let xs = (-8000..=8000).map(|i| i as f32 * 0.01);
        let (e, x) = worst_relative_error(xs, exp, f64::exp);
        assert!(e < 3e-7, "worst relative error {e} at x = {x}");
        assert_eq!(exp(0.0), 1.0);
    }

    #[test]
    fn ln_matches_f64_to_2e7() {
        let xs = (0..20000).map(|i| 1.0 + i as f32 * 0.37);
        let (e, x) = worst_relative_error(xs, ln, f64::ln);
        assert!(e < 2e-7, "worst relative error {e} at x = {x}");
        assert_eq!(ln(1.0), 0.0);
        assert!((ln(0.5) as f64 - 0.5f64.ln()).abs() < 1e-7);
    }
}

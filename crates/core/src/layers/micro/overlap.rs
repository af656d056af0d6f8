//! Overlapping features, docs/models.md §4 "Overlaps" [P §3.5, eq. 18], generalised to all features
//! at once as a log-mean-exp of depth magnitudes:
//!
//!   m = (1/β) · ln( 1 + (1/N) · Σ_i (exp(β·m_i) − 1) ),   β > 0, N ≥ 1,
//!
//! applied separately to depressions (heights < 0) and raised features (heights > 0); the two
//! results are added. With one feature and N = 1 this is eq. 18 with the map at 0.
//! The bake accumulates Σ (exp(β·m_i) − 1) per pixel with [`term`] (in a fixed feature
//! order) and finishes with [`resolve`]; [`combine`] is the same on a list.

use super::fastmath;

/// docs/models.md's β·m must stay below this so exp(β·m) is finite in f32 (the project refuses
/// settings where β × the deepest feature exceeds it).
pub const MAX_BETA_TIMES_DEPTH: f32 = 80.0;

/// exp(β·m) − 1 for a depth magnitude `m` ≥ 0 (0 for m = 0 exactly).
#[inline(always)]
pub fn term(m: f32, beta: f32) -> f32 {
    fastmath::exp(beta * m) - 1.0
}

/// The combined magnitude from an accumulated Σ terms (0 for 0).
#[inline(always)]
pub fn resolve(sum_terms: f32, beta: f32, inv_n: f32) -> f32 {
    fastmath::ln(1.0 + sum_terms * inv_n) * (1.0 / beta)
}

/// Combines signed feature heights at one pixel (depressions and raised parts separately).
pub fn combine(heights: &[f32], beta: f32, n: f32) -> f32 {
    let (mut neg, mut pos) = (0.0f32, 0.0f32);
    for &h in heights {
        if h < 0.0 {
            neg += term(-h, beta);
        } else {
            pos += term(h, beta);
        }
    }
    resolve(pos, beta, 1.0 / n) - resolve(neg, beta, 1.0 / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::close;

    #[test]
    fn nothing_covering_gives_zero() {
        assert_eq!(combine(&[], 4.0, 1.0), 0.0);
        assert_eq!(combine(&[0.0, 0.0], 4.0, 3.0), 0.0);
    }

    #[test]
    fn continuous_across_a_feature_edge() {
        // A feature fading to 0 at its edge changes the result continuously, with or without
        // another feature under it.
        for base in [&[][..], &[-0.7][..], &[-0.3, -1.2][..]] {
            let without = combine(base, 3.0, 2.0);
            let mut with = base.to_vec();
            with.push(-1e-4);
            let d = combine(&with, 3.0, 2.0) - without;
            assert!(
                d <= 0.0 && d > -1e-4,
                "step of {d} at the edge over {base:?}"
            );
        }
    }

    #[test]
    fn one_feature_with_n_1_keeps_its_depth() {
        for h in [-0.01, -0.5, -1.839, -2.5] {
            close(combine(&[h], 4.0, 1.0), h, 2e-6);
        }
        close(combine(&[0.8], 4.0, 1.0), 0.8, 2e-6);
    }

    #[test]
    fn two_equal_crossings_add_ln2_over_beta_not_double() {
        let (m, beta) = (1.5f32, 4.0f32);
        // ln(1 + 2(e^6 − 1))/4 = ln(2e^6 − 1)/4 = 1.5 + ln(2 − e^−6)/4 = 1.6726697
        let want = ((2.0f64 * (6.0f64).exp() - 1.0).ln() / 4.0) as f32;
        close(-combine(&[-m, -m], beta, 1.0), want, 2e-6);
        close(want, m + std::f32::consts::LN_2 / beta, 2e-3);
        assert!(want < 2.0 * m);
    }

    #[test]
    fn large_beta_keeps_the_deepest_small_beta_averages() {
        let hs = [-0.4, -1.0, -0.7];
        close(combine(&hs, 60.0, 1.0), -1.0, 0.02);
        // β → 0: (1/β)·ln(1 + (β/N)Σm) → Σm/N = 2.1/3 = 0.7
        close(combine(&hs, 1e-3, 3.0), -0.7, 2e-3);
    }

    #[test]
    fn depressions_and_raised_parts_combine_separately() {
        let (beta, n) = (4.0, 1.0);
        close(combine(&[-1.0, 0.5], beta, n), -1.0 + 0.5, 2e-6);
        close(
            combine(&[-1.0, -1.0, 0.5], beta, n),
            combine(&[-1.0, -1.0], beta, n) + 0.5,
            2e-6,
        );
    }
}

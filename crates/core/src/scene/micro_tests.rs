//! The micro-relief with age through the scene: pores stretch and furrows align along
//! the tension lines (docs/models.md §11 "Micro-relief with age").

use super::tests::{fresh, small};
use super::*;

/// The micro-relief tile baked at `years` with `edit` applied to the default project:
/// (the tile's heights, its side in mm, the pores).
fn micro_at(
    years: f32,
    edit: impl Fn(&mut Project),
) -> (HeightMap, f32, Vec<crate::layers::micro::pores::Pore>) {
    let mut p = Project::default();
    edit(&mut p);
    let t = p.age.mapping().t(years);
    let request = BakeRequest {
        micro_size_px: 512,
        ..small(t)
    };
    let s = fresh(&p, &request);
    (
        s.micro().unwrap().height.clone(),
        p.map_size_mm,
        s.relief().unwrap().pores().to_vec(),
    )
}

/// The aspect ratio and long-axis angle (degrees, 0–180) of the depression around
/// `centre_mm` within `reach_mm`: the depth-weighted second moments' eigenvalues.
fn depression_shape(h: &HeightMap, size_mm: f32, centre_mm: [f32; 2], reach_mm: f32) -> (f32, f32) {
    let n = h.width_px() as usize;
    let px = size_mm / n as f32;
    let (mut w, mut sxx, mut sxy, mut syy) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let lo = |c: f32| ((c - reach_mm) / px).floor().max(0.0) as usize;
    let hi = |c: f32| (((c + reach_mm) / px).ceil() as usize).min(n);
    for x in lo(centre_mm[0])..hi(centre_mm[0]) {
        for yu in lo(centre_mm[1])..hi(centre_mm[1]) {
            // Rows from the top, y in mm up from the bottom.
            let y = n - 1 - yu;
            let (dx, dy) = (
                (x as f32 + 0.5) * px - centre_mm[0],
                (yu as f32 + 0.5) * px - centre_mm[1],
            );
            if dx * dx + dy * dy > reach_mm * reach_mm {
                continue;
            }
            let d = f64::from((-h.data()[y * n + x]).max(0.0));
            w += d;
            sxx += d * f64::from(dx * dx);
            sxy += d * f64::from(dx * dy);
            syy += d * f64::from(dy * dy);
        }
    }
    let (a, b, c) = (sxx / w, sxy / w, syy / w);
    let mean = 0.5 * (a + c);
    let diff = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    let (l1, l2) = (mean + diff, (mean - diff).max(1e-12));
    let angle = (0.5 * (2.0 * b).atan2(a - c))
        .to_degrees()
        .rem_euclid(180.0);
    (((l1 / l2).sqrt()) as f32, angle as f32)
}

#[test]
fn pores_stretch_along_the_tension_lines_with_age() {
    // Pores only: no furrows, noise or warp, fewer and so more isolated.
    let pores_only = |p: &mut Project| {
        p.furrows.enabled = false;
        p.noise.strength = 0.0;
        p.warp.strength_mm = 0.0;
        p.pores.count = 150;
        p.pores.radius_mm = crate::project::MeanSpread::new(0.6, 0.1);
    };
    // The tension lines curve over the patch: each pore is measured against their
    // direction at its centre.
    let settings = {
        let mut p = Project::default();
        pores_only(&mut p);
        p.micro_settings().unwrap()
    };
    let mut medians = Vec::new();
    for years in [25.0, 75.0] {
        let (h, size, pores) = micro_at(years, pores_only);
        // Isolated pores away from the edges.
        let mut shapes: Vec<(f32, f32)> = pores
            .iter()
            .filter(|p| {
                let c = p.centre_mm;
                let clear = pores.iter().all(|q| {
                    q.centre_mm == c
                        || (q.centre_mm[0] - c[0]).hypot(q.centre_mm[1] - c[1]) > 5.0 * p.radius_mm
                });
                clear && c.iter().all(|&v| v > 3.0 && v < size - 3.0)
            })
            .map(|p| {
                let (aspect, angle) = depression_shape(&h, size, p.centre_mm, 2.2 * p.radius_mm);
                (
                    aspect,
                    angle - settings.tension_at(p.centre_mm).to_degrees(),
                )
            })
            .collect();
        assert!(shapes.len() > 20, "{} isolated pores", shapes.len());
        shapes.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (aspect, _) = shapes[shapes.len() / 2];
        let mut off: Vec<f32> = shapes
            .iter()
            .map(|s| {
                let d = s.1.rem_euclid(180.0);
                d.min(180.0 - d)
            })
            .collect();
        off.sort_by(f32::total_cmp);
        medians.push((aspect, off[off.len() / 2]));
    }
    eprintln!(
        "pore aspect, median angle off the local tension lines: 25 years {:?}, 75 years {:?}",
        medians[0], medians[1]
    );
    assert!(medians[0].0 < 1.15, "young pores round: {:?}", medians[0]);
    assert!(medians[1].0 >= 1.5, "old pores stretched: {:?}", medians[1]);
    assert!(medians[1].1 < 12.0, "old pores along θ: {:?}", medians[1]);
}

#[test]
fn furrows_grow_deeper_and_follow_the_tension_lines_with_age() {
    // Furrows only: pores of no depth (their places still link the furrows).
    let furrows_only = |p: &mut Project| {
        p.pores.depth = crate::project::MeanSpread::new(0.0, 0.0);
        p.noise.strength = 0.0;
        p.warp.strength_mm = 0.0;
    };
    let theta = Project::default().furrows.direction_deg.to_radians();
    let measure = |h: &HeightMap| {
        // The gradient's structure tensor over the tile: (λ1 − λ2)/(λ1 + λ2), and the
        // share of gradient energy across θ (gradients across furrows along θ).
        let n = h.width_px() as usize;
        let d = h.data();
        let (mut jxx, mut jxy, mut jyy) = (0.0f64, 0.0f64, 0.0f64);
        for y in 1..n - 1 {
            for x in 1..n - 1 {
                let gx = f64::from(d[y * n + x + 1] - d[y * n + x - 1]);
                // Rows from the top: up is −y.
                let gy = f64::from(d[(y - 1) * n + x] - d[(y + 1) * n + x]);
                jxx += gx * gx;
                jxy += gx * gy;
                jyy += gy * gy;
            }
        }
        let mean = 0.5 * (jxx + jyy);
        let diff = (0.25 * (jxx - jyy).powi(2) + jxy * jxy).sqrt();
        let anisotropy = diff / mean;
        // The unit normal to θ.
        let (nx, ny) = (-f64::from(theta.sin()), f64::from(theta.cos()));
        let across = (jxx * nx * nx + 2.0 * jxy * nx * ny + jyy * ny * ny) / (jxx + jyy);
        let rms = (d.iter().map(|v| f64::from(*v).powi(2)).sum::<f64>() / d.len() as f64).sqrt();
        (anisotropy, across, rms)
    };
    let (young, _, _) = micro_at(25.0, furrows_only);
    let (old, _, _) = micro_at(75.0, furrows_only);
    let (ay, cy, ry) = measure(&young);
    let (ao, co, ro) = measure(&old);
    eprintln!(
        "furrows: anisotropy {ay:.3} → {ao:.3}, gradient share across θ {cy:.3} → {co:.3}, rms {ry:.3} → {ro:.3}"
    );
    assert!(ao > ay + 0.15, "anisotropy {ay:.3} → {ao:.3}");
    assert!(co > cy, "across θ {cy:.3} → {co:.3}");
    assert!(ro > 1.3 * ry, "deeper: rms {ry:.3} → {ro:.3}");
}

//! CIELAB (D65) of linear sRGB, and the individual typology angle (ITA°) of a skin tone:
//! how the head's own colours are measured and compared (docs/models.md "Skin colour").

use glam::Vec3;

/// CIELAB L*, a*, b* of a linear sRGB colour (D65 white).
pub fn lab(rgb: Vec3) -> Vec3 {
    let x = 0.412_456_4 * rgb.x + 0.357_576_1 * rgb.y + 0.180_437_5 * rgb.z;
    let y = 0.212_672_9 * rgb.x + 0.715_152_2 * rgb.y + 0.072_175 * rgb.z;
    let z = 0.019_333_9 * rgb.x + 0.119_192 * rgb.y + 0.950_304_1 * rgb.z;
    let f = |t: f32| {
        if t > 216.0 / 24389.0 {
            t.cbrt()
        } else {
            (24389.0 / 27.0 * t + 16.0) / 116.0
        }
    };
    let (fx, fy, fz) = (f(x / 0.950_47), f(y), f(z / 1.088_83));
    Vec3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
}

/// The individual typology angle of a skin colour, degrees: atan((L* − 50)/b*). Over 55°
/// very light, 41–55 light, 28–41 intermediate, 10–28 tan, −30–10 brown, under −30 dark
/// (Chardon et al. 1991; Del Bino et al. 2006).
pub fn ita_degrees(lab: Vec3) -> f32 {
    (lab.x - 50.0).atan2(lab.z.max(1e-3)).to_degrees()
}

/// The ITA° group's name (see [`ita_degrees`]).
pub fn ita_group(ita: f32) -> &'static str {
    match ita {
        a if a > 55.0 => "very light",
        a if a > 41.0 => "light",
        a if a > 28.0 => "intermediate",
        a if a > 10.0 => "tan",
        a if a > -30.0 => "brown",
        _ => "dark",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_black_and_a_red_have_their_known_lab() {
        let w = lab(Vec3::ONE);
        assert!((w.x - 100.0).abs() < 0.05 && w.y.abs() < 0.05 && w.z.abs() < 0.05);
        assert!(lab(Vec3::ZERO).length() < 1e-3);
        // sRGB red: L* 53.24, a* 80.09, b* 67.20.
        let r = lab(Vec3::X);
        assert!(
            (r - Vec3::new(53.24, 80.09, 67.2)).abs().max_element() < 0.1,
            "{r}"
        );
    }

    #[test]
    fn light_skin_has_a_larger_angle_than_dark_skin() {
        assert!(ita_degrees(Vec3::new(70.0, 8.0, 16.0)) > 41.0);
        assert!(ita_degrees(Vec3::new(30.0, 8.0, 14.0)) < -30.0);
        assert_eq!(ita_group(60.0), "very light");
        assert_eq!(ita_group(-40.0), "dark");
    }
}

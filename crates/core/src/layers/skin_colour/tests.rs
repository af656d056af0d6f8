use super::*;
use crate::layers::hair::scalp::hair_age_alpha;
use crate::project::Project;
use crate::scene::Scene;

/// A point on the template's forehead (fully sun-exposed, no other region).
fn forehead() -> Vec3 {
    let l = &crate::head::fit::template().landmarks;
    l.get("glabella").unwrap() + Vec3::new(0.0, 0.03, 0.0)
}

/// Settings with only the age spots on.
fn spots_only() -> ColourSettings {
    ColourSettings {
        pale_amount: 0.0,
        mottle: 0.0,
        redness: 0.0,
        yellowing: 0.0,
        contrast_loss: 0.0,
        ..Project::default().colour_settings()
    }
}

/// The linear luminance of each texel of an sRGB picture.
fn luminance(img: &HeadImage) -> Vec<f32> {
    img.rgba
        .chunks_exact(4)
        .map(|p| {
            let c = Vec3::new(
                srgb_to_linear(p[0] as f32 / 255.0),
                srgb_to_linear(p[1] as f32 / 255.0),
                srgb_to_linear(p[2] as f32 / 255.0),
            );
            c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
        })
        .collect()
}

/// The texels of `mesh` (metres) at `size`², seed 1, with `template` as its template points.
fn texels_of(mesh: &Mesh, template: &dyn Fn(usize) -> Option<Vec3>, size: u32) -> SurfaceTexels {
    let regions = Regions::template().unwrap();
    let face = Face {
        regions,
        drawn_crease: &crate::layers::shape::drawn_crease,
        lower_lip: 0.0,
    };
    SurfaceTexels::new(mesh, template, 1.0, size, face, 1, &CancelToken::never()).unwrap()
}

/// The default head's texels at `size`² (its own points are the template's).
fn default_head_texels(scene: &Scene, size: u32) -> SurfaceTexels {
    let mesh = scene.mesh().clone();
    texels_of(&mesh, &|v| mesh.positions().get(v).copied(), size)
}

/// The default project's colour at 25 and at 80, and the default head's texels, at `n`².
fn young_and_old(n: usize) -> (HeadImage, HeadImage, SurfaceTexels) {
    let mut scene = Scene::new(Project::default()).unwrap();
    let cancel = CancelToken::never();
    scene.bake_colour(n as u32, 0.0, &cancel).unwrap();
    let young = scene.aged_colour().unwrap().as_ref().clone();
    scene.bake_colour(n as u32, 1.0, &cancel).unwrap();
    let old = scene.aged_colour().unwrap().as_ref().clone();
    (young, old, default_head_texels(&scene, n as u32))
}

#[test]
fn the_regions_lie_where_the_face_has_them() {
    let r = Regions::template().expect("the template's landmarks");
    let l = &crate::head::fit::template().landmarks;
    let at = |name: &str, offset_mm: [f32; 3]| l.get(name).unwrap() + Vec3::from(offset_mm) * 1e-3;
    // Forehead and nose in the sun; under the chin, the back of the head not.
    assert!(r.sun(at("glabella", [0.0, 30.0, 0.0])) > 0.95);
    assert!(r.sun(at("pronasale", [0.0, 0.0, 0.0])) > 0.95);
    assert!(r.sun(at("pogonion", [0.0, -60.0, -40.0])) < 0.05);
    assert!(r.sun(at("vertex", [0.0, -60.0, -90.0])) < 0.05);
    // A brow above each eye's middle, none on the cheek below it.
    for side in ["l", "r"] {
        let mid = 0.5
            * (l.get(&format!("endocanthion_{side}")).unwrap()
                + l.get(&format!("exocanthion_{side}")).unwrap());
        let above = mid + Vec3::new(0.0, 0.018, 0.005);
        assert!(r.brows(above) > 0.5, "brow {side}: {}", r.brows(above));
        assert!(r.brows(mid - Vec3::new(0.0, 0.03, 0.0)) == 0.0);
        assert!(r.eyes(mid) > 0.9);
        assert!(r.redness(mid - Vec3::new(0.0, 0.026, -0.005)) > 0.5);
    }
    // The beard wraps round the jaw's angle, behind the face's plane; the bare skin it
    // grays toward is the neck and the lower face, not the scalp nor the ear.
    for side in ["l", "r"] {
        let sx = if side == "l" { -1.0 } else { 1.0 };
        let tragion = format!("tragion_{side}");
        let angle = at(&tragion, [20.0 * sx, -65.0, 3.0]);
        assert!(
            r.beard(angle) > 0.5,
            "beard at the jaw's angle {side}: {}",
            r.beard(angle)
        );
        assert_eq!(r.bare_skin(at(&tragion, [0.0, 0.0, -20.0])), 0.0);
    }
    assert!(r.bare_skin(at("pogonion", [0.0, -60.0, -40.0])) > 0.95);
    assert_eq!(r.bare_skin(at("vertex", [0.0, -20.0, 0.0])), 0.0);
    assert_eq!(r.bare_skin(at("glabella", [0.0, 0.0, 0.0])), 0.0);
    let mouth = 0.5 * (at("cheilion_l", [0.0; 3]) + at("cheilion_r", [0.0; 3]));
    assert!(r.lips(mouth + Vec3::new(0.0, 0.0, 0.008)) > 0.9);
    assert_eq!(r.lips(at("glabella", [0.0; 3])), 0.0);
    // The under-eye crescent: below each eye (deepest toward the inner corner), not on
    // the brow nor the lower cheek.
    for side in ["l", "r"] {
        let inner = l.get(&format!("endocanthion_{side}")).unwrap();
        let outer = l.get(&format!("exocanthion_{side}")).unwrap();
        let below = |s: f32, mm: f32| inner.lerp(outer, s) - Vec3::new(0.0, mm * 1e-3, 0.0);
        let unit_mm = 0.5
            * l.get("exocanthion_l")
                .unwrap()
                .distance(l.get("exocanthion_r").unwrap())
            * 1e3;
        let trough = below(0.2, 0.33 * unit_mm);
        assert!(r.under_eye(trough) > 0.6, "{side}: {}", r.under_eye(trough));
        assert!(r.under_eye(below(0.2, 0.33 * unit_mm)) > r.under_eye(below(0.9, 0.33 * unit_mm)));
        assert_eq!(r.under_eye(below(0.5, -20.0)), 0.0);
        assert_eq!(r.under_eye(below(0.5, 40.0)), 0.0);
    }
}

#[test]
fn spots_are_2_to_10_mm_and_appear_one_by_one_from_the_onset() {
    let mut scene = Scene::new(Project::default()).unwrap();
    let cancel = CancelToken::never();
    scene.bake_colour(256, 1.0, &cancel).unwrap();
    let all = scene.age_spots().unwrap().clone();
    let spots: Vec<Spot> = all
        .iter()
        .filter(|s| s.kind == SpotKind::Lentigo)
        .copied()
        .collect();
    // The other kinds: a few keratoses, and the papules of the upper face.
    let count = |k| all.iter().filter(|s| s.kind == k).count();
    let (keratoses, papules) = (count(SpotKind::Keratosis), count(SpotKind::Papule));
    eprintln!("{keratoses} keratoses, {papules} papules");
    assert!((3..60).contains(&keratoses), "{keratoses}");
    assert!((20..800).contains(&papules), "{papules}");
    // The table's rows are in the kinds' order (a spot's kind indexes it).
    for (i, k) in SPOT_KINDS.iter().enumerate() {
        assert_eq!(k.kind as usize, i);
    }
    for s in all.iter() {
        let (lo, hi) = s.kind.params().diameter_mm;
        assert!((lo..=hi).contains(&s.diameter_mm), "{s:?}");
    }
    // About 0.6 lentigines per cm² over the exposed face, scalp and ears.
    assert!((100..1000).contains(&spots.len()), "{} spots", spots.len());
    let (lo, hi) = SPOT_DIAMETER_MM;
    assert!(spots.iter().all(|s| (lo..=hi).contains(&s.diameter_mm)));
    // Small spots are the common ones.
    let small = spots.iter().filter(|s| s.diameter_mm < 6.0).count();
    assert!(
        small * 2 > spots.len(),
        "{small} of {} under 6 mm",
        spots.len()
    );
    // The count at each age, by the project's spot curve (40 → 85 years).
    let p = Project::default();
    let shown = |years: f32| {
        let f = p.colour_factors(p.age.mapping().t(years)).spots;
        spots.iter().filter(|s| s.diameter_at(f) > 0.0).count()
    };
    let counts: Vec<usize> = [35.0, 40.0, 48.0, 65.0, 80.0].map(shown).to_vec();
    eprintln!(
        "{} spots; shown at 35/40/48/65/80 years: {counts:?}",
        spots.len()
    );
    assert_eq!(&counts[..2], &[0, 0], "{counts:?}");
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    assert!(counts[2] > 0 && counts[4] > 3 * counts[2], "{counts:?}");
    // A spot shows at 40 % of its size and grows to it.
    let s = spots[0];
    assert_eq!(s.diameter_at(s.appears), 0.0);
    assert!((s.diameter_at(s.appears + 1e-4) - 0.4 * s.diameter_mm).abs() < 0.01);
    assert_eq!(s.diameter_at(1.0).max(s.diameter_mm), s.diameter_mm);
}

/// Spots gather in patches: they lie where the cluster noise keeps them (mean chance of
/// being kept at least 1.5 times an even spread's of the same number, on the same head
/// and seed), so there are clusters and bare patches.
#[test]
fn age_spots_gather_in_patches() {
    let scene = Scene::new(Project::default()).unwrap();
    let mesh = scene.mesh().clone();
    let regions = Regions::template().unwrap();
    let kept = |tries: usize| {
        let points: Vec<Option<Vec3>> = mesh.positions().iter().map(|p| Some(*p)).collect();
        let spots = place_spots_gathered(
            &mesh,
            &points,
            1.0,
            regions,
            2.0,
            1,
            tries,
            SpotKind::Lentigo.params(),
        );
        let mean = spots
            .iter()
            .map(|s| spot_gathering(s.centre, 1))
            .sum::<f32>()
            / spots.len() as f32;
        (spots.len(), mean)
    };
    let (even_n, even) = kept(1);
    let (gathered_n, gathered) = kept(SPOT_CLUSTER_TRIES);
    eprintln!(
        "mean chance of being kept where the spots lie: {even:.3} even ({even_n}), \
         {gathered:.3} gathered ({gathered_n})"
    );
    assert_eq!(even_n, gathered_n, "the same number of spots");
    assert!(even_n > 500, "{even_n}");
    assert!(gathered > 1.5 * even, "{gathered} vs {even}");
}

#[test]
fn a_baked_spot_measures_its_diameter_in_millimetres() {
    // The 5 cm skin patch, in metres, all of it on the template's forehead.
    let mesh = crate::head::default::skin_patch();
    let point = forehead();
    let template = |_: usize| Some(point);
    let size = 500; // 0.1 mm a texel
    let texels = texels_of(&mesh, &template, size);
    // Three lone spots of known sizes, fully grown.
    let spot = |x_mm: f32, y_mm: f32, d: f32| Spot {
        kind: SpotKind::Lentigo,
        centre: Vec3::new(x_mm, y_mm, 0.0) * 1e-3,
        normal: Vec3::Z,
        diameter_mm: d,
        appears: 0.0,
        strength: 1.0,
        phases: [0.3, 1.9, 4.0],
    };
    let spots = [
        spot(-12.0, -12.0, 3.0),
        spot(10.0, -8.0, 8.0),
        spot(0.0, 11.0, 16.0),
    ];
    let factors = ColourFactors {
        spots: 1.0,
        ..ColourFactors::default()
    };
    let s = spots_only();
    let img = bake(None, &texels, &spots, &s, &factors, &CancelToken::never()).unwrap();
    let plain = luminance(
        &bake(
            None,
            &texels,
            &[],
            &s,
            &ColourFactors {
                spots: 1.0,
                ..Default::default()
            },
            &CancelToken::never(),
        )
        .unwrap(),
    );
    let lum = luminance(&img);
    let n = size as usize;
    let mm_per_texel = 50.0 / size as f32;
    for sp in spots {
        // Darkened by over a fifth of the spot's full darkening, within 15 mm of its centre.
        let (cx, cy) = (
            (sp.centre.x * 1000.0 + 25.0) / mm_per_texel,
            (25.0 - sp.centre.y * 1000.0) / mm_per_texel,
        );
        let mut area = 0usize;
        for y in 0..n {
            for x in 0..n {
                let d = ((x as f32 + 0.5 - cx).hypot(y as f32 + 0.5 - cy)) * mm_per_texel;
                let i = y * n + x;
                if d < 15.0 && lum[i] < plain[i] * (1.0 - 0.2 * 0.6) {
                    area += 1;
                }
            }
        }
        let diameter = 2.0 * (area as f32 / std::f32::consts::PI).sqrt() * mm_per_texel;
        let ratio = diameter / sp.diameter_mm;
        eprintln!("a {} mm spot measures {diameter:.2} mm", sp.diameter_mm);
        assert!(
            (0.75..=1.15).contains(&ratio),
            "a {} mm spot measures {diameter:.2} mm",
            sp.diameter_mm
        );
    }
}

/// The dark papules show on dark skin only, and lentigines less there (melanin hides
/// them): the same spots baked on a light and a dark skin colour.
#[test]
fn papules_show_on_dark_skin_and_lentigines_less() {
    let mesh = crate::head::default::skin_patch();
    let point = forehead();
    let template = |_: usize| Some(point);
    let size = 200;
    let texels = texels_of(&mesh, &template, size);
    let spot = |kind, x_mm: f32| Spot {
        kind,
        centre: Vec3::new(x_mm, 0.0, 0.0) * 1e-3,
        normal: Vec3::Z,
        diameter_mm: 3.0,
        appears: 0.0,
        strength: 1.0,
        phases: [0.3, 1.9, 4.0],
    };
    let spots = [spot(SpotKind::Lentigo, -10.0), spot(SpotKind::Papule, 10.0)];
    let factors = ColourFactors {
        spots: 1.0,
        ..ColourFactors::default()
    };
    // Each spot's darkest texel against the skin.
    let darkening = |albedo: [f32; 3]| {
        let s = ColourSettings {
            albedo,
            ..spots_only()
        };
        let lum =
            luminance(&bake(None, &texels, &spots, &s, &factors, &CancelToken::never()).unwrap());
        let skin = lum[(size as usize / 2) * size as usize + 5];
        let darkest = |x_mm: f32| {
            let x = ((x_mm + 25.0) / 50.0 * size as f32) as usize;
            (x - 3..=x + 3)
                .map(|x| lum[(size as usize / 2) * size as usize + x])
                .fold(f32::INFINITY, f32::min)
        };
        [1.0 - darkest(-10.0) / skin, 1.0 - darkest(10.0) / skin]
    };
    let light = darkening([0.7, 0.45, 0.33]);
    let dark = darkening([0.12, 0.05, 0.025]);
    eprintln!("lentigo, papule darkening: light skin {light:?}, dark skin {dark:?}");
    assert!(light[0] > 0.3 && light[1] < 0.02, "{light:?}");
    assert!(dark[1] > 0.3 && dark[0] < 0.7 * light[0], "{dark:?}");
}

#[test]
fn young_skin_is_its_own_colour_and_old_skin_is_uneven() {
    let mut scene = Scene::new(Project::default()).unwrap();
    let cancel = CancelToken::never();
    let p = Project::default();
    let n = 512usize;
    scene
        .bake_colour(n as u32, p.age.mapping().t(25.0), &cancel)
        .unwrap();
    let young = scene.aged_colour().unwrap().clone();
    scene.bake_colour(n as u32, 1.0, &cancel).unwrap();
    let old = scene.aged_colour().unwrap().clone();
    // At 25 nothing has started: the bake is the scan's colour map, resampled.
    let base = scene.colour_map().unwrap();
    let to_linear: Vec<f32> = (0..256).map(|c| srgb_to_linear(c as f32 / 255.0)).collect();
    let (x, y) = (n / 2, n * 3 / 10);
    let centre = |k: usize| (k as f32 + 0.5) / n as f32;
    let resampled = sample_linear(base, &to_linear, centre(x), centre(y));
    let i = (y * n + x) * 4;
    let c = Vec3::new(
        young.rgba[i] as f32,
        young.rgba[i + 1] as f32,
        young.rgba[i + 2] as f32,
    ) / 255.0;
    let expected = Vec3::new(
        linear_to_srgb(resampled.x),
        linear_to_srgb(resampled.y),
        linear_to_srgb(resampled.z),
    );
    assert!(
        (c - expected).abs().max_element() < 1.0 / 255.0 + 1e-4,
        "{c} vs {expected}"
    );
    // Unevenness: the spread of old/young luminance over the sun-exposed face.
    let texels = default_head_texels(&scene, n as u32);
    let (ly, lo) = (luminance(&young), luminance(&old));
    let ratios: Vec<f32> = (0..n * n)
        .filter(|&i| from_unit(texels.fields[i].sun) > 0.9 && ly[i] > 0.05)
        .map(|i| lo[i] / ly[i])
        .collect();
    assert!(ratios.len() > 5000, "{} exposed texels", ratios.len());
    let mean = ratios.iter().sum::<f32>() / ratios.len() as f32;
    let sd = (ratios.iter().map(|r| (r - mean).powi(2)).sum::<f32>() / ratios.len() as f32).sqrt();
    // Spots and blotches: the old face's tone varies by over 8 % where the young one's
    // is its own (0 by construction).
    eprintln!("old/young luminance over the exposed face: mean {mean:.3}, sd {sd:.3}");
    assert!(sd > 0.08, "old/young luminance: mean {mean:.3}, sd {sd:.3}");
    // Under 2 % of the face darker by a third: spots, not a dirty face.
    let dark = ratios.iter().filter(|&&r| r < mean * 0.67).count();
    assert!(
        dark * 50 < ratios.len(),
        "{dark} of {} much darker",
        ratios.len()
    );
}

#[test]
fn brows_gray_lips_fade_and_a_shadow_comes_under_the_eyes() {
    let cancel = CancelToken::never();
    let n = 512usize;
    let (young, old, texels) = young_and_old(n);
    let (ly, lo) = (luminance(&young), luminance(&old));
    let in_region = |f: fn(&Fields) -> u8| -> Vec<usize> {
        (0..n * n)
            .filter(|&i| texels.on_surface(i) && from_unit(f(&texels.fields[i])) > 0.9)
            .collect()
    };
    // Brow hair: the darkest quarter of the brows when young gets lighter.
    let mut brows = in_region(|f| f.brows);
    assert!(brows.len() > 100, "{} brow texels", brows.len());
    brows.sort_by(|&a, &b| ly[a].total_cmp(&ly[b]));
    let hair = &brows[..brows.len() / 4];
    let mean = |v: &[f32], idx: &[usize]| idx.iter().map(|&i| v[i]).sum::<f32>() / idx.len() as f32;
    eprintln!(
        "brow hair luminance {:.3} → {:.3}",
        mean(&ly, hair),
        mean(&lo, hair)
    );
    assert!(
        mean(&lo, hair) > 1.5 * mean(&ly, hair),
        "brow hair {} → {}",
        mean(&ly, hair),
        mean(&lo, hair)
    );
    // Lips: their redness (r − g over luminance) falls.
    let lips = in_region(|f| f.lips);
    let redness = |img: &HeadImage| {
        lips.iter()
            .map(|&i| (img.rgba[4 * i] as f32 - img.rgba[4 * i + 1] as f32) / 255.0)
            .sum::<f32>()
            / lips.len() as f32
    };
    assert!(
        redness(&old) < 0.85 * redness(&young),
        "lips r − g {} → {}",
        redness(&young),
        redness(&old)
    );
    // And they thin: their outer part (the red's border) keeps less of its redness than
    // their middle (by the mouth's line).
    let kept = |part: &dyn Fn(&Fields) -> bool| {
        let idx: Vec<usize> = lips
            .iter()
            .copied()
            .filter(|&i| part(&texels.fields[i]))
            .collect();
        let r = |img: &HeadImage| {
            idx.iter()
                .map(|&i| (img.rgba[4 * i] as f32 - img.rgba[4 * i + 1] as f32) / 255.0)
                .sum::<f32>()
                / idx.len().max(1) as f32
        };
        (r(&old) / r(&young), idx.len())
    };
    let (rim, n_rim) = kept(&|f| from_unit(f.lip_rim) > 0.8);
    let (middle, n_middle) = kept(&|f| from_unit(f.lip_rim) < 0.1);
    eprintln!(
        "lips' redness kept: {rim:.2} at the rim ({n_rim} texels), {middle:.2} in the middle ({n_middle})"
    );
    assert!(n_rim > 20 && n_middle > 20, "{n_rim} {n_middle}");
    assert!(rim < middle - 0.05, "rim {rim}, middle {middle}");
    // Under the eyes: darker with age, and not without the shadow.
    let under = in_region(|f| f.under_eye);
    assert!(under.len() > 50, "{} under-eye texels", under.len());
    let mut project = Project::default();
    project.skin.under_eye = 0.0;
    let mut plain = Scene::new(project).unwrap();
    plain.bake_colour(n as u32, 1.0, &cancel).unwrap();
    let lp = luminance(plain.aged_colour().unwrap());
    let (shadowed, without) = (mean(&lo, &under), mean(&lp, &under));
    eprintln!("under-eye luminance at 80 {shadowed:.3}, {without:.3} without the shadow");
    assert!(shadowed < 0.92 * without, "{shadowed} vs {without}");
    let outside = in_region(|f| f.brows);
    assert_eq!(mean(&lo, &outside), mean(&lp, &outside));
}

/// The old brow grays hair by hair (some hair stays dark, some turns light: salt and
/// pepper, not a gray strip), in streaks along the brow (the draw varies less along it
/// than across), and grows bushier beyond the young brow's hair.
#[test]
fn the_old_brow_is_salt_and_pepper_in_streaks_and_bushier() {
    let mut scene = Scene::new(Project::default()).unwrap();
    let cancel = CancelToken::never();
    let n = 1024usize;
    scene.bake_colour(n as u32, 0.0, &cancel).unwrap();
    let young = scene.aged_colour().unwrap().clone();
    scene.bake_colour(n as u32, 1.0, &cancel).unwrap();
    let old = scene.aged_colour().unwrap().clone();
    let (ly, lo) = (luminance(&young), luminance(&old));
    let texels = default_head_texels(&scene, n as u32);
    let mut brows: Vec<usize> = (0..n * n)
        .filter(|&i| from_unit(texels.fields[i].brows) > 0.9)
        .collect();
    brows.sort_by(|&a, &b| ly[a].total_cmp(&ly[b]));
    // The young brow's hair: its darkest quarter.
    let hair = &brows[..brows.len() / 4];
    let share = |f: &dyn Fn(f32) -> bool| {
        hair.iter().filter(|&&i| f(lo[i] / ly[i].max(1e-4))).count() as f32 / hair.len() as f32
    };
    let (kept, gray) = (share(&|r| r < 1.6), share(&|r| r > 2.5));
    eprintln!("brow hair at 80: {kept:.2} stays dark, {gray:.2} turns light");
    assert!(kept > 0.2 && gray > 0.2, "{kept} dark, {gray} light");
    // Bushier: the lighter half of the young brow region (skin between and around the
    // hairs) takes hair at 80, dark or gray: a share of its texels darkens or lightens by
    // a quarter or more (the paling alone moves them less; 0.09 measured, none without the
    // bushier brow).
    let skin = &brows[brows.len() / 2..];
    let grown = skin
        .iter()
        .filter(|&&i| (lo[i] / ly[i].max(1e-4) - 1.0).abs() > 0.25)
        .count() as f32
        / skin.len() as f32;
    eprintln!("brow skin at 80: {grown:.2} of it takes hair");
    assert!(grown > 0.06, "{grown}");
    // Streaks: the draw two millimetres along the brow is closer than two across it.
    let r = Regions::template().unwrap();
    let l = &crate::head::fit::template().landmarks;
    let (mut along, mut across) = (0.0, 0.0);
    for side in ["l", "r"] {
        let inner = l.get(&format!("endocanthion_{side}")).unwrap();
        let outer = l.get(&format!("exocanthion_{side}")).unwrap();
        for k in 0..200 {
            let s = k as f32 / 200.0;
            let p = inner.lerp(outer, s) + Vec3::new(0.0, 0.016 + 0.00003 * k as f32, 0.005);
            // Two millimetres along the arch: out along x, then back to the same
            // height above the brow's middle line.
            let mut a = p + Vec3::new(0.002, 0.0, 0.0);
            a.y -= (r.brow_coords(a).y - r.brow_coords(p).y) * 1e-3;
            let draw = |q: Vec3| value3(brow_streak(r, q), 5);
            along += (draw(a) - draw(p)).abs();
            across += (draw(p + Vec3::new(0.0, 0.002, 0.0)) - draw(p)).abs();
        }
    }
    eprintln!("brow draw change over 2 mm: {along:.1} along, {across:.1} across");
    assert!(along < 0.5 * across, "{along} along, {across} across");
}

#[test]
fn the_bake_is_the_same_on_any_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut scene = Scene::new(Project::default()).unwrap();
            scene.bake_colour(256, 1.0, &CancelToken::never()).unwrap();
            scene.aged_colour().unwrap().rgba.clone()
        })
    };
    assert!(run(1) == run(3), "bytes differ between 1 and 3 threads");
    // Another seed, other spots.
    let mut p = Project::default();
    p.skin.colour_seed = 2;
    let mut scene = Scene::new(p).unwrap();
    scene.bake_colour(256, 1.0, &CancelToken::never()).unwrap();
    assert!(scene.aged_colour().unwrap().rgba != run(2));
}

#[test]
fn the_shown_colour_carries_the_hair_ages_in_its_alpha_with_a_soft_edge() {
    use crate::layers::hair::transition::{DistanceMetric, HairRegions, TransitionTexture};
    // Hair on the left half of the layout (all of it staying), none on the right.
    let n = 64u32;
    let outer: Vec<bool> = (0..n * n).map(|i| i % n < n / 2).collect();
    let regions = HairRegions::from_bools(n, n, &outer, &outer).unwrap();
    let transition = TransitionTexture::from_regions(&regions, DistanceMetric::Chebyshev).unwrap();
    let aged = HeadImage {
        width_px: 200,
        height_px: 200,
        rgba: vec![128; 200 * 200 * 4],
    };
    let shown = with_alpha(&aged, Some(&hair_age_alpha(&transition, 200, 200)), None);
    let alpha = |x: usize| shown.rgba[4 * (100 * 200 + x) + 3];
    // Deep in the hair: a = 1 (byte 255); far from it: none (0); across the edge (at
    // x = 100) it falls over the blur's box (2 % of 200 px: 4 px each side).
    assert_eq!((alpha(20), alpha(180)), (255, 0));
    let ramp: Vec<u8> = (94..107).map(alpha).collect();
    assert!(ramp.windows(2).all(|w| w[0] >= w[1]), "{ramp:?}");
    assert!(
        ramp.iter().filter(|&&a| a > 0 && a < 255).count() >= 6,
        "{ramp:?}"
    );
    // The colour itself is the aged colour's.
    assert!(
        shown
            .rgba
            .chunks_exact(4)
            .all(|p| p[..3] == [128, 128, 128])
    );
    // Without hair, no tint anywhere.
    let bare = with_alpha(&aged, None, None);
    assert!(bare.rgba.chunks_exact(4).all(|p| p[3] == 0));
}

/// The stubble grays over the bare skin's colour: at 80 the beard's hue (blue over red)
/// is near the neck's below it, where at 25 the dark stubble grayed it (toward the
/// beard's own tone, the jaw stayed gray over a pink neck: "a colour seam", blind).
#[test]
fn the_gray_beard_takes_the_colour_of_the_bare_skin_round_it() {
    let n = 512usize;
    let (young, old, texels) = young_and_old(n);
    let pick = |keep: &dyn Fn(&Fields) -> bool| -> Vec<usize> {
        (0..n * n).filter(|&i| keep(&texels.fields[i])).collect()
    };
    let beard = pick(&|f| from_unit(f.beard) > 0.9);
    let bare = pick(&|f| from_unit(f.bare) > 0.9 && f.beard == 0);
    assert!(
        beard.len() > 500 && bare.len() > 500,
        "{} {}",
        beard.len(),
        bare.len()
    );
    // Mean linear blue over red.
    let hue = |img: &HeadImage, idx: &[usize]| {
        let c = idx.iter().fold(Vec3::ZERO, |acc, &i| {
            let p = &img.rgba[4 * i..4 * i + 3];
            acc + Vec3::new(
                srgb_to_linear(p[0] as f32 / 255.0),
                srgb_to_linear(p[1] as f32 / 255.0),
                srgb_to_linear(p[2] as f32 / 255.0),
            )
        });
        c.z / c.x
    };
    let gap = |img: &HeadImage| hue(img, &beard) - hue(img, &bare);
    let (at_25, at_80) = (gap(&young), gap(&old));
    eprintln!("beard's blue/red over the bare skin's: {at_25:.3} at 25, {at_80:.3} at 80");
    assert!(at_25 > 0.05, "{at_25}");
    // Toward it, not all the way: the stubble grays, it does not vanish (the hair is
    // about four fifths gray at 80).
    assert!(at_80.abs() < 0.6 * at_25, "{at_25} → {at_80}");
    assert!(at_80 > 0.2 * at_25, "{at_25} → {at_80}");
}

/// The bags cast a shadow along the lid–cheek junction, narrower than the mesh's
/// triangles, so the colour draws it: darker there at 80 with the bags' shape, the same
/// without it (strength 0 or the shape off), and nowhere else.
#[test]
fn the_bags_shadow_the_lid_cheek_junction_with_their_shape() {
    let cancel = CancelToken::never();
    let n = 512usize;
    let (_, old, texels) = young_and_old(n);
    let lo = luminance(&old);
    let junction: Vec<usize> = (0..n * n)
        .filter(|&i| from_unit(texels.fields[i].crease) > 0.9)
        .collect();
    let elsewhere: Vec<usize> = (0..n * n)
        .filter(|&i| texels.fields[i].crease == 0 && texels.on_surface(i))
        .collect();
    assert!(junction.len() > 20, "{} junction texels", junction.len());
    let mean = |v: &[f32], idx: &[usize]| idx.iter().map(|&i| v[i]).sum::<f32>() / idx.len() as f32;
    let without = |edit: fn(&mut Project)| {
        let mut project = Project::default();
        edit(&mut project);
        let mut scene = Scene::new(project).unwrap();
        scene.bake_colour(n as u32, 1.0, &cancel).unwrap();
        luminance(scene.aged_colour().unwrap())
    };
    for plain in [
        without(|p| p.shape.bags = 0.0),
        without(|p| p.shape.enabled = false),
    ] {
        let (shadowed, unshadowed) = (mean(&lo, &junction), mean(&plain, &junction));
        eprintln!("the junction's luminance at 80 {shadowed:.3}, {unshadowed:.3} without the bags");
        // (Half the shadow it drew before the shape's relief drew the bags' crease
        // itself: 0.88 of the luminance, was 0.77; halved again with the contact shadows
        // and the softer crease: 0.945.)
        assert!(shadowed < 0.97 * unshadowed, "{shadowed} vs {unshadowed}");
        assert_eq!(mean(&lo, &elsewhere), mean(&plain, &elsewhere));
    }
    // Under each eye, a band a few millimetres tall.
    let frame = Regions::template().unwrap();
    for side in [-1.0f32, 1.0] {
        let q = junction
            .iter()
            .filter_map(|&i| {
                let q = frame.relative(texels.position[i]);
                (q.x * side > 0.0).then_some(q)
            })
            .collect::<Vec<_>>();
        assert!(q.len() > 10, "{side}: {}", q.len());
        assert!(
            q.iter()
                .all(|q| (0.2..1.1).contains(&q.x.abs()) && (-0.5..-0.1).contains(&q.y))
        );
    }
}

/// The skin's islands are padded ([`texels::PAD_PX`]) into the texels nothing covers, not
/// into another part's: two skin islands 10 texels apart (the lips' parting) meet in the
/// gap, an eye's island beside them keeps its texels, and the pad is aged as skin but not
/// on the surface.
#[test]
fn the_pad_fills_the_gap_between_islands_and_spares_other_parts() {
    use crate::head::mesh::{MeshPart, RawMesh};
    let n = 64u32;
    let px = |x: f32, y: f32| Vec2::new(x / n as f32, 1.0 - y / n as f32);
    // Skin: two quads, columns 4–20 and 30–46 (a 10-texel gap); an eye: columns 50–60.
    let quad = |x0: f32, x1: f32| [px(x0, 4.0), px(x1, 4.0), px(x1, 40.0), px(x0, 40.0)];
    let mut uvs = Vec::new();
    for (x0, x1) in [(4.0, 20.0), (30.0, 46.0), (50.0, 60.0)] {
        uvs.extend(quad(x0, x1));
    }
    let positions: Vec<Vec3> = uvs.iter().map(|uv| Vec3::new(uv.x, uv.y, 0.0)).collect();
    let indices: Vec<u32> = (0..3u32)
        .flat_map(|q| [0, 1, 2, 0, 2, 3].map(|k| 4 * q + k))
        .collect();
    let part = |name: &str, first: u32, count: u32| MeshPart {
        name: name.into(),
        first_triangle: first,
        triangle_count: count,
    };
    let raw = RawMesh {
        positions,
        uvs: Some(uvs),
        indices,
        parts: vec![
            part("object \"head\"", 0, 4),
            part("object \"eye_l\"", 4, 2),
        ],
        ..Default::default()
    };
    let mesh = crate::Mesh::build(raw, "islands").unwrap();
    let regions = Regions::template().unwrap();
    let face = Face {
        regions,
        drawn_crease: &|_| 0.0,
        lower_lip: 0.0,
    };
    let texels =
        SurfaceTexels::new(&mesh, &|_| None, 1.0, n, face, 1, &CancelToken::never()).unwrap();
    let at = |x: usize, y: usize| y * n as usize + x;
    // The gap's middle row: every texel aged as skin, none of them on the surface.
    for x in 22..28 {
        assert!(texels.covers_skin(at(x, 20)), "gap texel {x}");
        assert!(
            !texels.on_surface(at(x, 20)),
            "gap texel {x} on the surface"
        );
    }
    // Inside an island: on the surface.
    assert!(texels.on_surface(at(10, 20)));
    // The eye's texels stay the eye's; beyond the pad's reach nothing is skin.
    for x in 51..59 {
        assert!(!texels.covers_skin(at(x, 20)), "eye texel {x}");
    }
    assert!(!texels.covers_skin(at(10, 52)), "12 texels below an island");
    assert!(texels.covers_skin(at(10, 46)), "6 texels below an island");
}

/// Painted hair thins and grays; the skin around it does not: a texel a little darker than
/// the measured skin tone (under [`PAINTED_SKIN_SHARE`] of the way to the hair) keeps its
/// colour where the paint goes, a texel of paint goes to the skin by the share lost. (Taken
/// for paint, the darker forehead under a woman's kept hairline paled into "a pale band
/// like the edge of a bald cap", blind.)
#[test]
fn only_paint_goes_with_the_hair() {
    let (bald, hair) = (Vec3::splat(0.2), Vec3::splat(0.02));
    let painted = PaintedHair {
        ages: &[],
        t: 1.0,
        bald,
        hair,
        thinned: [0.6, 0.3],
        keeps_hairline: true,
    };
    // A crown texel (the male pattern's hair goes at 0.5), not gray.
    let byte = 1 + (0.5f32 * 254.0).round() as u8;
    let age = |c: Vec3| painted.age(c, byte, 0.0, Vec3::ONE);
    let skin = bald.lerp(hair, 0.8 * PAINTED_SKIN_SHARE);
    assert_eq!(age(skin), skin);
    let paint = age(hair);
    assert!((paint.x - (0.02 + 0.6 * 0.18)).abs() < 1e-5, "{paint}");
    // Between them, continuous: no edge where skin becomes paint.
    let just = bald.lerp(hair, PAINTED_SKIN_SHARE + 0.01);
    assert!((age(just) - just).length() < 2e-3, "{}", age(just));
    // Below the kept hairline no strand grows: the paint stays.
    assert_eq!(painted.age(hair, 1 + 10, 0.0, Vec3::ONE), hair);
}

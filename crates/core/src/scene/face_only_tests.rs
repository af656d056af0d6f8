//! A face-only mesh (a MediaPipe/ARKit-style mask: forehead to chin, cheek to cheek, no
//! ears, scalp or neck), in centimetres: its units from the face, its landmarks found, its
//! wrinkles in place, and no hair (nothing to grow it on).

use glam::Vec3;

use super::*;
use crate::head::fit::template;

/// A head cut to its face — triangles in front of its ears, from above its brows to
/// below its chin, within 7 cm of the midline, facing forward — written in centimetres
/// (`to_cm`: its units to centimetres), its UVs kept; and its landmarks in centimetres.
fn face_mask(
    dir: &std::path::Path,
    head: &Mesh,
    landmarks: &crate::head::landmarks::Landmarks,
    to_cm: f32,
) -> (std::path::PathBuf, crate::head::landmarks::Landmarks) {
    let cm = |p: Vec3| p * to_cm;
    let (glabella, chin, tragion) = (
        cm(landmarks.get("glabella").unwrap()),
        cm(landmarks.get("pogonion").unwrap()),
        cm(landmarks
            .get("tragion_r")
            .or_else(|| landmarks.get("tragion_l"))
            .unwrap()),
    );
    let (top, bottom, behind) = (glabella.y + 4.5, chin.y - 1.5, tragion.z + 3.0);
    let mid = glabella.x;
    let mut raw = crate::head::mesh::RawMesh::default();
    let mut uvs = Vec::new();
    let mut copies = std::collections::HashMap::new();
    for [a, b, c] in head.triangles() {
        let p = [a, b, c].map(|i| cm(head.positions()[i as usize]));
        let centre = (p[0] + p[1] + p[2]) / 3.0;
        let normal = (p[1] - p[0]).cross(p[2] - p[0]);
        let keep = centre.y < top
            && centre.y > bottom
            && centre.z > behind
            && (centre.x - mid).abs() < 7.0
            && normal.z > 0.0;
        if !keep {
            continue;
        }
        for i in [a, b, c] {
            let v = *copies.entry(i).or_insert_with(|| {
                raw.positions.push(cm(head.positions()[i as usize]));
                uvs.push(head.uvs()[i as usize]);
                raw.positions.len() as u32 - 1
            });
            raw.indices.push(v);
        }
    }
    raw.uvs = Some(uvs);
    let mesh = Mesh::build(raw, "face mask").unwrap();
    let path = dir.join("face-cm.obj");
    std::fs::write(&path, crate::head::mesh::obj::to_obj(&mesh, |p| p)).unwrap();
    let mut truth = crate::head::landmarks::Landmarks::default();
    for name in crate::head::landmarks::NAMES {
        if let Some(p) = landmarks.get(name) {
            truth.set(name, cm(p)).unwrap();
        }
    }
    (path, truth)
}

/// A face-only mask of `head` in centimetres, its units, axes and landmarks found from
/// the face; returns its scene, baked with hair asked for.
fn check_face_mask(
    name: &str,
    head: &Mesh,
    landmarks: &crate::head::landmarks::Landmarks,
    to_cm: f32,
) -> Scene {
    let dir = tempfile::tempdir().unwrap();
    let (path, truth) = face_mask(dir.path(), head, landmarks, to_cm);
    let mut p = Project::default();
    p.mesh.path = Some(path);
    p.mesh.metres_per_unit = None;
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.strength = 0.0;
    let mut scene = Scene::new(p).unwrap();
    eprintln!(
        "{name}: {} triangles; units {:?}; axes {:?} ({}); layout {}",
        scene.mesh().triangle_count(),
        scene.units(),
        scene.axes(),
        scene.axes_how(),
        scene.layout().how
    );
    // Units from the face: centimetres.
    assert_eq!(
        scene.units().metres_per_unit,
        0.01,
        "{name}: {}",
        scene.units().how
    );
    assert_eq!(
        scene.axes(),
        crate::head::mesh::units::Axes::STANDARD,
        "{name}: {}",
        scene.axes_how()
    );
    // The landmarks found within 0.15 of the eye corners' distance of those placed by
    // hand on this face, each.
    let found = scene.layout().landmarks.clone().expect("landmarks found");
    let eyes = truth
        .get("exocanthion_r")
        .unwrap()
        .distance(truth.get("exocanthion_l").unwrap());
    let mut worst = (0.0f32, "");
    for n in crate::head::landmarks::NAMES {
        let (Some(f), Some(t)) = (found.get(n), truth.get(n)) else {
            continue;
        };
        let off = f.distance(t) / eyes;
        eprintln!("  {n}: {off:.3} of the eye distance");
        if off > worst.0 {
            worst = (off, n);
        }
    }
    assert!(
        worst.0 < 0.15,
        "{name}: {} is {:.2} of the eye distance off",
        worst.1,
        worst.0
    );
    // Nothing found where the mask has nothing: the top of the head, the ears.
    for n in ["vertex", "tragion_r", "tragion_l"] {
        assert!(
            found.get(n).is_none(),
            "{name}: {n} found on a face-only mesh"
        );
    }
    // No hair: nothing to grow it on, and it says so.
    let with_hair = BakeRequest {
        hair: true,
        ..BakeRequest::maps(256, 1.0, false)
    };
    scene.bake(&with_hair, &CancelToken::never()).unwrap();
    assert!(
        scene.hair().is_none_or(|h| h.is_empty()),
        "{name}: hair on a face mask"
    );
    assert!(
        scene.layout().how.contains("face only"),
        "{}",
        scene.layout().how
    );
    scene
}

/// The default head's face and the MakeHuman head's (its landmarks placed by hand), each
/// in centimetres: measured, fitted and aged in place without a scalp.
#[test]
fn a_face_only_mask_in_centimetres_is_measured_fitted_and_aged_in_place() {
    let default = crate::head::default::default_head();
    let scene = check_face_mask("default head", &default, &template().landmarks, 100.0);
    let dir = super::heads_tests::heads_dir().join("makehuman");
    let mh = Mesh::load(&dir.join("mh_head.obj")).unwrap();
    let mh_landmarks =
        crate::head::landmarks::Landmarks::load(&dir.join("landmarks.json")).unwrap();
    let mpu = crate::head::mesh::units::detect(&mh.bounds(), Some(&mh_landmarks)).metres_per_unit;
    check_face_mask("makehuman", &mh, &mh_landmarks, mpu * 100.0);
    // The wrinkles in place: the mask keeps the template's UVs, so its large-wrinkle map
    // is the default head's where the mask has skin.
    let mask = scene.large().unwrap().height.data().to_vec();
    let mut reference = Scene::new(Project {
        pores: scene.project().pores.clone(),
        furrows: scene.project().furrows.clone(),
        noise: scene.project().noise.clone(),
        ..Project::default()
    })
    .unwrap();
    reference
        .bake(&BakeRequest::maps(256, 1.0, false), &CancelToken::never())
        .unwrap();
    let template_map = reference.large().unwrap().height.data().to_vec();
    let (mut dot, mut na, mut nb) = (0.0f64, 0.0f64, 0.0f64);
    for (a, b) in mask.iter().zip(&template_map) {
        if *a != 0.0 || *b != 0.0 {
            dot += f64::from(a * b);
            na += f64::from(a * a);
            nb += f64::from(b * b);
        }
    }
    let correlation = dot / (na.sqrt() * nb.sqrt()).max(1e-12);
    eprintln!("wrinkles' correlation with the default head's: {correlation:.3}");
    assert!(correlation > 0.8, "{correlation}");
}

/// Whole heads (closed round the back, their necks cut) are not taken for face-only
/// masks: the scan, the MakeHuman head and the four panel heads; nor is a flat patch of
/// skin (it faces one way, but has no depth).
#[test]
fn whole_heads_are_not_face_only() {
    let dir = super::heads_tests::heads_dir();
    let mut files = vec![
        dir.join("lee-perry-smith/LeePerrySmith.glb"),
        dir.join("makehuman/mh_head.obj"),
    ];
    for name in [
        "african-female",
        "african-male",
        "asian-male",
        "caucasian-female",
    ] {
        files.push(dir.join(format!("panel/{name}.obj")));
    }
    let heads = files
        .iter()
        .map(|f| (f.display().to_string(), Mesh::load(f).unwrap()))
        .chain([(
            "default head".to_owned(),
            crate::head::default::default_head(),
        )]);
    for (name, mesh) in heads {
        assert!(
            crate::head::fit::auto::face_only(&mesh).is_none(),
            "{name} taken for a face only"
        );
    }
}

//! `agesim export` and the export code the editor shares with it: the aged head as GLB
//! read back with the `gltf` crate, maps at an age, all-or-nothing on errors and cancels.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cli;

use cli::{agesim, stderr};

use agesim::export::{ExportRequest, GlbOut, MapsOut};
use agesim_core::cancel::CancelToken;
use agesim_core::project::Project;

#[test]
fn the_aged_head_glb_loads_back_with_its_material() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("head.glb");
    let o = agesim(&[
        "export",
        "--age-years",
        "70",
        "--size",
        "256",
        "--glb",
        glb.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (doc, buffers, images) = gltf::import(&glb).expect("the GLB imports");
    let material = doc.materials().next().expect("a material");
    assert!(material.name().unwrap().contains("70 years"));
    let pbr = material.pbr_metallic_roughness();
    // The default head's own colour map, aged: a skin tone on average.
    let colour = pbr.base_color_texture().expect("a base colour texture");
    let image = &images[colour.texture().source().index()];
    let channels = image.pixels.len() / (image.width * image.height) as usize;
    let texels: Vec<&[u8]> = image.pixels.chunks_exact(channels).collect();
    let mean = |c: usize| texels.iter().map(|p| f64::from(p[c])).sum::<f64>() / texels.len() as f64;
    let (r, g, b) = (mean(0), mean(1), mean(2));
    assert!(r > g && g > b, "a skin tone, got {r} {g} {b}");
    assert_eq!(pbr.base_color_factor()[3], 1.0);
    let normal = material.normal_texture().expect("a normal texture");
    let image = &images[normal.texture().source().index()];
    assert_eq!((image.width, image.height), (256, 256));
    // A tangent-space normal map: mostly +z, with the wrinkles bending it.
    let pixels: Vec<&[u8]> = image.pixels.chunks_exact(3).collect();
    let mean = |c: usize| pixels.iter().map(|p| f64::from(p[c])).sum::<f64>() / pixels.len() as f64;
    assert!(mean(2) > 230.0, "mean blue {}", mean(2));
    // Centred on (0, 0, 1) = (128, 128, 255): the bends average out. A map encoded
    // twice centres on 191.
    for c in [0, 1] {
        assert!(
            (mean(c) - 127.5).abs() < 4.0,
            "channel {c} mean {}",
            mean(c)
        );
    }
    let bent = pixels
        .iter()
        .filter(|p| (i32::from(p[0]) - 128).abs() > 20)
        .count();
    assert!(bent > 100, "only {bent} texels bent by wrinkles");
    // The skin has the aged material; the eye sockets (not skin) a plain one.
    for mesh in doc.meshes() {
        let skin = !mesh.name().unwrap_or_default().contains("eye sockets");
        for prim in mesh.primitives() {
            assert_eq!(prim.material().index(), Some(usize::from(!skin)));
            assert_eq!(prim.material().normal_texture().is_some(), skin);
            let reader = prim.reader(|b| Some(&buffers[b.index()]));
            assert!(reader.read_tangents().is_some(), "tangents are written");
            assert!(reader.read_tex_coords(0).is_some());
        }
    }
    // The height map beside it, and the file says where it is.
    assert!(dir.path().join("head_wrinkle_height.png").is_file());
    let bytes = std::fs::read(&glb).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    assert_eq!(json["extras"]["height_map"], "head_wrinkle_height.png");
    assert_eq!(json["extras"]["age_years"], 70.0);
}

/// A head with its own colour map exports it, paled for the age, as the material's
/// `baseColorTexture` (the factor then white): the artist's texture work is kept.
#[test]
fn a_colour_map_is_exported_aged_as_the_base_colour_texture() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("colour.png");
    image::RgbImage::from_pixel(16, 8, image::Rgb([150, 60, 40]))
        .save(&map)
        .unwrap();
    let head = dir.path().join("head.glb");
    std::fs::write(&head, agesim_core::head::DEFAULT_HEAD_GLB).unwrap();
    let mut project = Project::default();
    project.mesh.path = Some(head);
    project.mesh.colour_map = Some(map);
    let project_file = dir.path().join("p.agesim.json");
    std::fs::write(&project_file, project.to_json_pretty()).unwrap();
    let glb = dir.path().join("aged.glb");
    let mut images_at = Vec::new();
    for years in ["20", "80"] {
        let o = agesim(&[
            "export",
            "--project",
            project_file.to_str().unwrap(),
            "--age-years",
            years,
            "--size",
            "64",
            "--glb",
            glb.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (doc, _, images) = gltf::import(&glb).expect("the GLB imports");
        let pbr = doc.materials().next().unwrap().pbr_metallic_roughness();
        assert_eq!(pbr.base_color_factor(), [1.0; 4]);
        let texture = pbr.base_color_texture().expect("a base colour texture");
        let image = images[texture.texture().source().index()].clone();
        assert_eq!((image.width, image.height), (16, 8));
        images_at.push(image.pixels[..4].to_vec());
    }
    // Young: the map as it is; old: paler (toward the pale tone, every channel up).
    assert_eq!(&images_at[0][..3], &[150, 60, 40]);
    let (young, old) = (&images_at[0], &images_at[1]);
    assert!((0..3).all(|c| old[c] > young[c]), "{young:?} → {old:?}");
}

#[test]
fn maps_at_two_ages_differ_and_the_old_one_is_deeper() {
    let dir = tempfile::tempdir().unwrap();
    let mut ranges = Vec::new();
    for years in ["25", "75"] {
        let exr = dir.path().join(format!("h{years}.exr"));
        let o = agesim(&[
            "export",
            "--age-years",
            years,
            "--size",
            "128",
            "--height-exr",
            exr.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let img = exr::prelude::read_first_flat_layer_from_file(&exr).unwrap();
        let (lo, hi) = img.layer_data.channel_data.list[0]
            .sample_data
            .values_as_f32()
            .fold((f32::MAX, f32::MIN), |(lo, hi), h| (lo.min(h), hi.max(h)));
        ranges.push(hi - lo);
    }
    assert!(ranges[1] > ranges[0] * 1.2, "relief by age: {ranges:?}");
}

#[test]
fn a_bad_request_or_a_cancel_leaves_the_old_files_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let normal = dir.path().join("normal.png");
    let glb = dir.path().join("head.glb");
    std::fs::write(&normal, b"old").unwrap();
    // Cancelled while the GLB's maps bake: the maps already staged must not appear.
    let token = CancelToken::new();
    let request = ExportRequest {
        years: 60.0,
        maps: MapsOut {
            size_px: 128,
            normal_png: Some(normal.clone()),
            ..MapsOut::default()
        },
        glb: Some(GlbOut {
            path: glb.clone(),
            size_px: 256,
        }),
        ..ExportRequest::default()
    };
    let progress = |f: f32, _: &str| {
        if f > 0.5 {
            token.cancel();
        }
    };
    let err = agesim::export::run(&Project::default(), None, &request, &progress, &token)
        .expect_err("cancelled");
    assert!(err.to_string().contains("cancel"), "{err:#}");
    assert_eq!(std::fs::read(&normal).unwrap(), b"old");
    assert!(!glb.exists());
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["normal.png"], "no temporary is left");

    // A GLB named .gltf is refused before anything is written, naming the file.
    let o = agesim(&[
        "export",
        "--size",
        "64",
        "--normal-png",
        normal.to_str().unwrap(),
        "--glb",
        dir.path().join("head.gltf").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("head.gltf"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&normal).unwrap(), b"old");
    // So is a size beyond the engine's range, naming the value.
    let o = agesim(&[
        "export",
        "--size",
        "80000",
        "--normal-png",
        normal.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("80000"), "{}", stderr(&o));
}

/// The GLB is in metres whatever the head file's units: the default head written in
/// centimetres comes back at its size in metres.
#[test]
fn the_glb_is_in_metres_for_a_head_in_centimetres() {
    let dir = tempfile::tempdir().unwrap();
    let head = agesim_core::head::default_head();
    let obj = dir.path().join("head-cm.obj");
    std::fs::write(&obj, agesim_core::mesh::obj::to_obj(&head, |p| p * 100.0)).unwrap();
    let mut project = Project::default();
    project.mesh.path = Some(obj);
    let project_file = dir.path().join("p.agesim.json");
    std::fs::write(&project_file, project.to_json_pretty()).unwrap();
    let glb = dir.path().join("cm.glb");
    let o = agesim(&[
        "export",
        "--project",
        project_file.to_str().unwrap(),
        "--size",
        "64",
        "--glb",
        glb.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (doc, buffers, _) = gltf::import(&glb).unwrap();
    let mut top = f32::NEG_INFINITY;
    let mut bottom = f32::INFINITY;
    for mesh in doc.meshes() {
        for prim in mesh.primitives() {
            let reader = prim.reader(|b| Some(&buffers[b.index()]));
            for p in reader.read_positions().unwrap() {
                top = top.max(p[1]);
                bottom = bottom.min(p[1]);
            }
        }
    }
    let want = head.bounds().size().y;
    assert!(
        ((top - bottom) / want - 1.0).abs() < 0.01,
        "{} m tall, want {want}",
        top - bottom
    );
}

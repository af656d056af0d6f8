//! `agesim export` and the export code the editor shares with it: the aged head as GLB
//! read back with the `gltf` crate, maps at an age, all-or-nothing on errors and cancels.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cli;

use cli::{agesim, stderr};

use agesim::export::{ExportRequest, GlbOut, MapsOut};
use agesim_core::base::cancel::CancelToken;
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
    // The creases' cavity occlusion, as the view darkens them: open skin white, the
    // bottoms of the wrinkles darker.
    let occlusion = material.occlusion_texture().expect("an occlusion texture");
    // One texture, glTF's channels: occlusion red, roughness green, metallic blue.
    let orm = pbr
        .metallic_roughness_texture()
        .expect("a roughness texture");
    assert_eq!(
        orm.texture().source().index(),
        occlusion.texture().source().index()
    );
    let ao = &images[occlusion.texture().source().index()];
    assert_eq!((ao.width, ao.height), (256, 256));
    let channels = ao.pixels.len() / (256 * 256);
    let open = ao
        .pixels
        .chunks_exact(channels)
        .filter(|p| p[0] == 255)
        .count();
    let dark = ao
        .pixels
        .chunks_exact(channels)
        .filter(|p| p[0] < 200)
        .count();
    assert!(
        open > 256 * 256 * 3 / 4 && dark > 30,
        "{open} open, {dark} dark texels"
    );
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
    // The skin has the aged material; the eye sockets (not skin) a plain one, which reads
    // the skin's base colour texture as the view does (the eyes drawn on blank eyeballs
    // are in it).
    let colour_texture = |m: gltf::Material| {
        m.pbr_metallic_roughness()
            .base_color_texture()
            .map(|t| t.texture().index())
    };
    let skin_colour = doc.materials().next().and_then(colour_texture);
    assert!(skin_colour.is_some());
    for mesh in doc.meshes().filter(|m| m.name() != Some("hair")) {
        let skin = !mesh.name().unwrap_or_default().contains("eye sockets");
        for prim in mesh.primitives() {
            assert_eq!(prim.material().index(), Some(usize::from(!skin)));
            assert_eq!(prim.material().normal_texture().is_some(), skin);
            assert_eq!(colour_texture(prim.material()), skin_colour);
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
    std::fs::write(&head, agesim_core::head::default::DEFAULT_HEAD_GLB).unwrap();
    let mut project = Project::default();
    project.mesh.path = Some(head);
    project.mesh.colour_map = Some(map);
    let project_file = dir.path().join("p.agesim.json");
    std::fs::write(&project_file, project.to_json_pretty()).unwrap();
    let glb = dir.path().join("aged.glb");
    let mut images_at = Vec::new();
    let mut roughness = Vec::new();
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
        // The roughness in the texture's green (its factor 1 keeps it), metallic none.
        assert_eq!(pbr.roughness_factor(), 1.0);
        let orm = pbr
            .metallic_roughness_texture()
            .expect("a roughness texture");
        let orm = &images[orm.texture().source().index()];
        let mut green: Vec<u8> = orm.pixels.chunks_exact(3).map(|p| p[1]).collect();
        assert!(orm.pixels.chunks_exact(3).all(|p| p[2] == 0), "metallic");
        green.sort_unstable();
        roughness.push(f32::from(green[green.len() / 2]) / 255.0);
        let texture = pbr.base_color_texture().expect("a base colour texture");
        let image = images[texture.texture().source().index()].clone();
        // Baked over the head's UVs at the colour map's size, at least 1024².
        assert_eq!((image.width, image.height), (1024, 1024));
        let channels = image.pixels.len() / (1024 * 1024);
        let mean = |c: usize| {
            image
                .pixels
                .chunks_exact(channels)
                .map(|p| f64::from(p[c]))
                .sum::<f64>()
                / (1024.0 * 1024.0)
        };
        images_at.push([mean(0), mean(1), mean(2)]);
    }
    // Young: the map as it is; old: sallower (less red against green and blue, the
    // paling tint and the yellowing), and uneven.
    assert_eq!(images_at[0], [150.0, 60.0, 40.0]);
    let (young, old) = (images_at[0], images_at[1]);
    assert!(old[1] / old[0] > young[1] / young[0], "{young:?} → {old:?}");
    // Old skin is drier: the skin's roughness young, rougher old (docs/models.md "Sheen").
    assert!(
        (roughness[0] - project.skin.roughness).abs() < 0.5 / 255.0,
        "{roughness:?}"
    );
    assert!(roughness[1] > roughness[0] + 0.1, "{roughness:?}");
}

/// The GLB's base colour at 80 has the age spots and the uneven tone; at 25 it is the
/// head's own colour, as even as it was (nothing has started).
#[test]
fn the_old_base_colour_is_uneven_and_the_young_one_even() {
    let dir = tempfile::tempdir().unwrap();
    let texture_at = |years: &str| {
        let glb = dir.path().join(format!("head-{years}.glb"));
        let o = agesim(&[
            "export",
            "--age-years",
            years,
            "--size",
            "512",
            "--glb",
            glb.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (doc, _, images) = gltf::import(&glb).expect("the GLB imports");
        let pbr = doc.materials().next().unwrap().pbr_metallic_roughness();
        let texture = pbr.base_color_texture().expect("a base colour texture");
        let image = images[texture.texture().source().index()].clone();
        let channels = image.pixels.len() / (image.width * image.height) as usize;
        let lum: Vec<f64> = image
            .pixels
            .chunks_exact(channels)
            .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
            .collect();
        (image.width, lum)
    };
    let (n20, at20) = texture_at("20");
    let (n25, at25) = texture_at("25");
    let (n80, at80) = texture_at("80");
    assert_eq!((n20, n25), (n80, n80));
    assert!(at25 == at20, "at 25 the colour is the head's own, as at 20");
    // The face's middle (the default head's layout: the face in the middle of the map).
    let n = n80 as usize;
    let face: Vec<usize> = (n * 3 / 10..n * 6 / 10)
        .flat_map(|y| (n * 3 / 10..n * 7 / 10).map(move |x| y * n + x))
        .filter(|&i| at25[i] > 60.0)
        .collect();
    let ratios: Vec<f64> = face.iter().map(|&i| at80[i] / at25[i]).collect();
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    let sd = (ratios.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / ratios.len() as f64).sqrt();
    // Spots: small patches darker by a tenth than the tone around them.
    let spots = ratios.iter().filter(|&&r| r < 0.9 * mean).count();
    eprintln!(
        "old/young over the face: mean {mean:.3}, sd {sd:.3}, {spots} spot texels of {}",
        ratios.len()
    );
    assert!(sd > 0.03, "sd {sd:.3}");
    assert!(
        spots > 100 && spots * 10 < ratios.len(),
        "{spots} of {}",
        ratios.len()
    );
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
            hair: agesim::export::GlbHair::default(),
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
    let head = agesim_core::head::default::default_head();
    let obj = dir.path().join("head-cm.obj");
    std::fs::write(
        &obj,
        agesim_core::head::mesh::obj::to_obj(&head, |p| p * 100.0),
    )
    .unwrap();
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
    for mesh in doc.meshes().filter(|m| m.name() != Some("hair")) {
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
    // The hair is in metres too: on the head, standing at most 2 cm above its top.
    let hair = doc
        .meshes()
        .find(|m| m.name() == Some("hair"))
        .expect("hair");
    let prim = hair.primitives().next().unwrap();
    let reader = prim.reader(|b| Some(&buffers[b.index()]));
    let hair_top = reader
        .read_positions()
        .unwrap()
        .fold(f32::NEG_INFINITY, |m, p| m.max(p[1]));
    assert!(
        hair_top > top - 0.03 && hair_top < top + 0.02,
        "hair top {hair_top}, head {top}"
    );
}

/// A UDIM head's maps are written one per tile (`height.1001.png`, …, each the size asked
/// for), by `export` and `bake`; its GLB has a material per tile, each with its tile's
/// maps, and UVs in [0, 1] as those maps are laid out.
#[test]
fn a_udim_head_is_exported_tile_by_tile() {
    let dir = tempfile::tempdir().unwrap();
    let obj = cli::udim_head(dir.path());
    let o = cli::agesim(&["mesh-info", obj.to_str().unwrap()]);
    assert!(
        cli::stdout(&o).contains("udim:      tiles 1001, 1002"),
        "{}",
        cli::stdout(&o)
    );

    let maps = dir.path().join("maps");
    let glb = dir.path().join("head.glb");
    let o = agesim(&[
        "export",
        "--mesh",
        obj.to_str().unwrap(),
        "--age-years",
        "75",
        "--size",
        "128",
        "--height-png",
        maps.join("height.png").to_str().unwrap(),
        "--normal-png",
        maps.join("normal.png").to_str().unwrap(),
        "--roughness-png",
        maps.join("roughness.png").to_str().unwrap(),
        "--ao-png",
        maps.join("ao.png").to_str().unwrap(),
        "--base-colour-png",
        maps.join("colour.png").to_str().unwrap(),
        "--glb",
        glb.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let listed = cli::stdout(&o);
    for name in [
        "maps/height.1001.png",
        "maps/height.1002.png",
        "maps/normal.1001.png",
        "maps/normal.1002.png",
        "maps/roughness.1001.png",
        "maps/ao.1002.png",
        "head_wrinkle_height.1001.png",
        "head_wrinkle_height.1002.png",
    ] {
        let path = dir.path().join(name);
        assert!(listed.contains(name), "{name} not listed: {listed}");
        let image = image::open(&path).unwrap();
        assert_eq!((image.width(), image.height()), (128, 128), "{name}");
    }
    assert!(!maps.join("height.png").exists());
    // The aged base colour per tile too, at the colour's own size.
    for n in [1001, 1002] {
        assert!(
            maps.join(format!("colour.{n}.png")).is_file(),
            "colour tile {n}"
        );
    }
    // Both tiles carry wrinkles (the forehead lines cross the midline).
    for n in [1001, 1002] {
        let h = image::open(maps.join(format!("height.{n}.png")))
            .unwrap()
            .into_luma16();
        let (lo, hi) = h
            .pixels()
            .fold((u16::MAX, 0), |(lo, hi), p| (lo.min(p[0]), hi.max(p[0])));
        assert!(hi - lo > 10_000, "tile {n}: heights {lo}..{hi}");
    }

    let (doc, buffers, images) = gltf::import(&glb).expect("the GLB imports");
    let skin: Vec<_> = doc
        .materials()
        .filter(|m| m.name().is_some_and(|n| n.contains("UDIM")))
        .collect();
    assert_eq!(skin.len(), 2);
    for (m, n) in skin.iter().zip([1001, 1002]) {
        assert!(m.name().unwrap().ends_with(&format!("UDIM {n}")));
        let normal = m.normal_texture().expect("a normal map per tile");
        let image = &images[normal.texture().source().index()];
        assert_eq!((image.width, image.height), (128, 128));
    }
    let mut skin_primitives = 0;
    for mesh in doc.meshes().filter(|m| m.name() != Some("hair")) {
        for prim in mesh.primitives() {
            let reader = prim.reader(|b| Some(&buffers[b.index()]));
            for uv in reader.read_tex_coords(0).unwrap().into_f32() {
                assert!(uv.iter().all(|c| (-1e-4..=1.0001).contains(c)), "{uv:?}");
            }
            skin_primitives +=
                usize::from(prim.material().name().is_some_and(|n| n.contains("UDIM")));
        }
    }
    assert_eq!(skin_primitives, 2, "one skin primitive per tile");

    let out = dir.path().join("bake");
    let o = agesim(&[
        "bake",
        "--mesh",
        obj.to_str().unwrap(),
        "--size",
        "64",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("bake.json")).unwrap()).unwrap();
    assert_eq!(report["udim_tiles"], serde_json::json!([1001, 1002]));
    for name in [
        "head_Height.1001.exr",
        "head_Height.1002.exr",
        "head_Normal.1002.png",
        "head_BaseColor.1002.png",
        "head_Roughness.1001.png",
        "head_AO.1002.png",
    ] {
        assert!(out.join(name).exists(), "{name}");
        let listed = report["outputs"].as_array().unwrap();
        assert!(
            listed.contains(&serde_json::json!(name)),
            "{name}: {listed:?}"
        );
    }
    // Too large a size per tile for the atlas is refused, naming the tiles.
    let o = agesim(&[
        "bake",
        "--mesh",
        obj.to_str().unwrap(),
        "--size",
        "16384",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("UDIM tiles"), "{}", stderr(&o));
}

/// The aged head's morph targets (docs/models.md §13 "Exported"), read back with the
/// `gltf` crate: `age` (every region's full move) and `old_age` (what the old age adds),
/// two targets per primitive, their weights at 65 (the old age's 0) and at 85 (the full
/// move's 1, the old age's part way), and the full move in metres: 1–25 mm at most, on
/// the face, downward on the whole; the old age a part of it — on the default head and on
/// the MakeHuman head (decimetres, its own landmarks).
#[test]
fn the_glb_carries_the_age_morph_targets() {
    let dir = tempfile::tempdir().unwrap();
    let heads = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/heads/makehuman");
    for (name, extra) in [
        ("default", vec![]),
        (
            "makehuman",
            vec![
                "--mesh".to_owned(),
                format!("{heads}/mh_head.obj"),
                "--landmarks".to_owned(),
                format!("{heads}/landmarks.json"),
            ],
        ),
    ] {
        let glb = dir.path().join(format!("{name}.glb"));
        let mut args = vec![
            "export".to_owned(),
            "--age-years".to_owned(),
            "65".to_owned(),
            "--size".to_owned(),
            "64".to_owned(),
            "--glb".to_owned(),
            glb.to_str().unwrap().to_owned(),
        ];
        args.extend(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = agesim(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        // At 85 (on a range that reaches it) the full move is whole and the old age on
        // its way.
        let old_glb = dir.path().join(format!("{name}-85.glb"));
        let mut old_args = args.clone();
        old_args[2] = "85";
        old_args[6] = old_glb.to_str().unwrap();
        old_args.extend(["--set", "age.old_years=90"]);
        let o = agesim(&old_args);
        assert!(o.status.success(), "{}", stderr(&o));
        let (old_doc, _, _) = gltf::import(&old_glb).expect("the GLB imports");
        for mesh in old_doc.meshes().filter(|m| m.name() != Some("hair")) {
            let w = mesh.weights().expect("default weights");
            assert_eq!(w[0], 1.0, "{name} at 85: {w:?}");
            assert!(w[1] > 0.5 && w[1] < 1.0, "{name} at 85: {w:?}");
        }
        let (doc, buffers, _) = gltf::import(&glb).expect("the GLB imports");
        // The target's name, in each mesh's extras (the JSON chunk).
        let bytes = std::fs::read(&glb).unwrap();
        let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
        // The head's meshes (the hair beside them is at the age: no target).
        for m in json["meshes"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|m| m["name"] != "hair")
        {
            assert_eq!(
                m["extras"]["targetNames"],
                serde_json::json!(["age", "old_age"]),
                "{name}"
            );
        }
        let (mut largest, mut down, mut moved) = (0.0f32, 0.0f32, 0usize);
        let mut old_largest = 0.0f32;
        let mut weight = None;
        for mesh in doc.meshes().filter(|m| m.name() != Some("hair")) {
            let w = mesh.weights().expect("default weights");
            assert_eq!(w.len(), 2);
            assert_eq!(w[1], 0.0, "{name}: no old age at 65");
            weight = Some(w[0]);
            for prim in mesh.primitives() {
                assert_eq!(prim.morph_targets().count(), 2, "{name}: two targets");
                let reader = prim.reader(|b| Some(&buffers[b.index()]));
                let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
                let mut targets = reader.read_morph_targets();
                for (k, (dp, dn, dt)) in targets.by_ref().enumerate() {
                    let dp: Vec<[f32; 3]> = dp.expect("position deltas").collect();
                    assert!(dn.is_some() && dt.is_some(), "normal and tangent deltas");
                    assert_eq!(dp.len(), positions.len());
                    for d in &dp {
                        let mm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() * 1000.0;
                        if k == 1 {
                            old_largest = old_largest.max(mm);
                            continue;
                        }
                        largest = largest.max(mm);
                        down += d[1];
                        moved += usize::from(mm > 0.5);
                    }
                }
            }
        }
        assert!(
            old_largest > 0.5 && old_largest < largest,
            "{name}: the old age's largest {old_largest} mm, the full move's {largest}"
        );
        let weight = weight.unwrap();
        eprintln!(
            "{name}: largest {largest:.2} mm, {moved} vertices over 0.5 mm, Σ dy {down:.4} m, weight at 65: {weight:.3}"
        );
        assert!((1.0..=25.0).contains(&largest), "{name}: {largest} mm");
        assert!(down < 0.0, "{name}: downward on the whole");
        assert!(moved > 100, "{name}: {moved}");
        assert!(weight > 0.3 && weight < 1.0, "{name}: weight {weight}");
    }
}

/// The GLB carries the aged hair and brows as a mesh named `hair` (a ribbon per strand,
/// its vertex colours the strand's): light is a quarter of full, none leaves it out; at 80
/// its strands are two groups, pigmented and gray; at 25 none is gray.
#[test]
fn the_glb_carries_the_aged_hair() {
    let dir = tempfile::tempdir().unwrap();
    let colours = std::cell::RefCell::new(Vec::<(String, Vec<u8>)>::new());
    let hair = |years: &str, which: &str| {
        let glb = dir.path().join(format!("{years}-{which}.glb"));
        let o = agesim(&[
            "export",
            "--age-years",
            years,
            "--size",
            "64",
            "--glb-hair",
            which,
            "--glb",
            glb.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (doc, buffers, images) = gltf::import(&glb).expect("the GLB imports");
        // The skin's base colour is the same with or without the hair in the file.
        let colour = doc.materials().next().unwrap().pbr_metallic_roughness();
        let colour = &images[colour
            .base_color_texture()
            .unwrap()
            .texture()
            .source()
            .index()];
        colours
            .borrow_mut()
            .push((years.to_owned(), colour.pixels.clone()));
        let node = doc.nodes().find(|n| n.name() == Some("hair"))?;
        let prim = node.mesh().unwrap().primitives().next().unwrap();
        assert!(prim.material().double_sided());
        let reader = prim.reader(|b| Some(&buffers[b.index()]));
        let triangles = reader.read_indices().unwrap().into_u32().count() / 3;
        let colours: Vec<[f32; 4]> = reader.read_colors(0).unwrap().into_rgba_f32().collect();
        assert_eq!(colours.len(), reader.read_positions().unwrap().count());
        Some((triangles, colours))
    };
    let (light, old) = hair("80", "light").expect("a hair mesh");
    let (full, _) = hair("80", "full").expect("a hair mesh");
    // The exported head read back by agesim keeps its own UVs: the hair is left out.
    let back = agesim_core::head::mesh::Mesh::load(&dir.path().join("80-light.glb")).unwrap();
    assert!(!back.report().uvs_generated, "{:?}", back.report().warnings);
    assert!(back.parts().iter().all(|p| !p.name.contains("hair")));
    assert!(hair("80", "none").is_none(), "no hair asked, none written");
    {
        let colours = colours.borrow();
        let at_80: Vec<&Vec<u8>> = colours
            .iter()
            .filter(|(y, _)| y == "80")
            .map(|(_, c)| c)
            .collect();
        assert_eq!(at_80.len(), 3);
        assert!(
            at_80.iter().all(|c| *c == at_80[0]),
            "the base colour changed with the hair"
        );
    }
    let ratio = full as f64 / light as f64;
    assert!(
        (2.5..4.5).contains(&ratio),
        "full {full}, light {light} triangles"
    );
    // Gray strands light, pigmented ones dark, few between (each hair one or the other).
    let share = |c: &[[f32; 4]], f: &dyn Fn(f32) -> bool| {
        c.iter().filter(|c| f(c[1])).count() as f64 / c.len() as f64
    };
    let (gray, dark) = (share(&old, &|g| g > 0.25), share(&old, &|g| g < 0.08));
    assert!(
        gray > 0.3 && dark > 0.05,
        "at 80: {gray:.2} gray, {dark:.2} dark"
    );
    let (_, young) = hair("25", "light").expect("a hair mesh");
    assert!(share(&young, &|g| g > 0.25) < 0.01, "gray at 25");
}

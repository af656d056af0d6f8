//! The editor's files and comforts, driven through its menus, shortcuts and windows with
//! egui_kittest: wrinkle files with errors, undo / redo, save and reopen, the unsaved-
//! changes prompt, presets, and exports (cancelled, and a GLB read back). File dialogs are
//! scripted ([`ScriptedDialogs`]): each answer is the path a person would pick.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};
use std::sync::Arc;

use agesim::editor::files::ScriptedDialogs;
use agesim::editor::{EditorApp, EditorOptions};
use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;

mod common;
use common::{drag, fibre_count, harness_with, large_map, map_point, settle, wait_for};

/// A harness whose dialogs answer from `dialogs` and whose presets live in `dir`.
fn scripted(dialogs: &Arc<ScriptedDialogs>, dir: &Path) -> Harness<'static, EditorApp> {
    let mut h = harness_with(EditorOptions {
        dialogs: Some(dialogs.clone()),
        config_dir: Some(dir.join("config")),
        ..EditorOptions::default()
    });
    settle(&mut h);
    h
}

/// Clicks a menu of the menu bar, then one of its entries.
fn menu(h: &mut Harness<'static, EditorApp>, menu: &str, entry: &str) {
    h.get_by_role_and_label(Role::Button, menu).click();
    h.run_steps(2);
    // An entry's name carries its shortcut ("Open project… Ctrl+O").
    h.get_by(|n| n.role() == Role::Button && n.label().is_some_and(|l| l.starts_with(entry)))
        .click();
    h.run_steps(2);
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_wrinkle_file_with_errors_is_refused_with_its_lines_and_the_fibres_are_kept() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.wrk");
    std::fs::write(
        &bad,
        "# three bad lines\n!\nma=0.4;0.7\nmb=0.5;x\nn=three\nrelWidth=-1\n",
    )
    .unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    dialogs.answer(Some(bad));
    let mut h = scripted(&dialogs, dir.path());
    let (fibres, map) = (fibre_count(&h), large_map(&h));
    menu(&mut h, "File", "Load wrinkle file…");
    wait_for(&mut h, "the error", |app| !app.open_errors().is_empty());
    assert_eq!(dialogs.asked(), ["Load wrinkle file"]);
    let error = h.state().open_errors().join("\n");
    for line in [":4:", ":5:", ":6:"] {
        assert!(
            error.contains(&format!("bad.wrk{line}")),
            "{line} in: {error}"
        );
    }
    settle(&mut h);
    assert_eq!(fibre_count(&h), fibres, "the old fibres are kept");
    assert_eq!(large_map(&h), map);
    assert!(!h.state().modified());
}

#[test]
fn undo_and_redo_restore_a_slider_drag_and_a_fibre_drag() {
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    // A slider dragged by hand over several frames is one step.
    let gamma0 = h.state().project().large.gamma;
    let slider = h.get_by_role_and_label(Role::Slider, "gamma").rect();
    drag(
        &mut h,
        slider.center(),
        slider.center() + egui::vec2(60.0, 0.0),
    );
    settle(&mut h);
    let gamma1 = h.state().project().large.gamma;
    assert!(gamma1 > gamma0, "the drag moved gamma: {gamma0} → {gamma1}");
    assert!(h.state().modified() && h.state().title().ends_with("* — agesim"));
    // The fibre's end dragged on the map.
    let fibre = h.state().wrinkles()[0].file.groups[0].fibre.clone();
    let start = map_point(&mut h, fibre.ma());
    drag(&mut h, start, start + egui::vec2(-25.0, 12.0));
    settle(&mut h);
    let moved = h.state().wrinkles()[0].file.groups[0].fibre.clone();
    assert_ne!(moved.ma(), fibre.ma());
    // Undo the fibre drag, then the slider drag, each with one Ctrl+Z.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(
        h.state().wrinkles()[0].file.groups[0].fibre.ma(),
        fibre.ma()
    );
    assert_eq!(h.state().project().large.gamma, gamma1);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(h.state().project().large.gamma, gamma0);
    assert!(!h.state().modified(), "back at the opened state");
    // Redo both: Ctrl+Shift+Z and Ctrl+Y.
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    settle(&mut h);
    assert_eq!(h.state().project().large.gamma, gamma1);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Y);
    settle(&mut h);
    assert_eq!(
        h.state().wrinkles()[0].file.groups[0].fibre.ma(),
        moved.ma()
    );
    // The Edit menu names the step.
    h.get_by_role_and_label(Role::Button, "Edit").click();
    h.run_steps(2);
    assert!(h.query_by_label_contains("Undo fibre drag").is_some());
}

#[test]
fn save_then_reopen_gives_the_same_state() {
    let dir = tempfile::tempdir().unwrap();
    let path: PathBuf = dir.path().join("old man.agesim.json");
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    h.get_by_role_and_label(Role::Slider, "depth")
        .set_value_accesskit(2.0);
    h.get_by_role_and_label(Role::Button, "Add fibre").click();
    settle(&mut h);
    let (fibres, map, project) = (fibre_count(&h), large_map(&h), h.state().project().clone());
    // Ctrl+S on an untitled document asks where.
    dialogs.answer(Some(path.clone()));
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    wait_for(&mut h, "the save", |app| !app.modified());
    assert_eq!(h.state().title(), "old man.agesim.json — agesim");
    // The edited built-in wrinkle files and their mask are written beside it.
    let names = files_in(dir.path());
    for f in [
        "old man-forehead.wrk",
        "old man-wrinkle-mask.png",
        "old man.agesim.json",
    ] {
        assert!(names.iter().any(|n| n == f), "{f} in {names:?}");
    }
    // New, then File › Open project….
    h.key_press_modifiers(Modifiers::COMMAND, Key::N);
    settle(&mut h);
    assert_ne!(fibre_count(&h), fibres);
    dialogs.answer(Some(path.clone()));
    menu(&mut h, "File", "Open project…");
    wait_for(&mut h, "the open", |app| app.path() == Some(path.as_path()));
    settle(&mut h);
    assert_eq!(fibre_count(&h), fibres);
    assert_eq!(h.state().project().large.depth, project.large.depth);
    assert_eq!(h.state().project().age, project.age);
    assert_eq!(h.state().project().pores, project.pores);
    assert_eq!(
        large_map(&h),
        map,
        "the reopened project bakes the same map"
    );
    assert!(!h.state().modified());
}

#[test]
fn the_unsaved_changes_prompt_keeps_or_drops_the_changes() {
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    h.get_by_role_and_label(Role::Slider, "depth")
        .set_value_accesskit(2.5);
    settle(&mut h);
    h.key_press_modifiers(Modifiers::COMMAND, Key::N);
    h.run_steps(2);
    assert!(h.query_by_label("Unsaved changes").is_some());
    h.get_by_role_and_label(Role::Button, "Cancel").click();
    h.run_steps(2);
    assert!(h.query_by_label("Unsaved changes").is_none());
    assert_eq!(
        h.state().project().large.depth,
        2.5,
        "Cancel keeps the changes"
    );
    // Save, then cancel the save dialog: nothing is saved and New does not follow,
    // not even after a later save.
    h.key_press_modifiers(Modifiers::COMMAND, Key::N);
    h.run_steps(2);
    h.get_by_role_and_label(Role::Button, "Save").click();
    wait_for(&mut h, "the cancelled dialog", |_| {
        dialogs.asked().len() == 1
    });
    h.run_steps(3);
    assert_eq!(h.state().project().large.depth, 2.5);
    let path = dir.path().join("kept.agesim.json");
    dialogs.answer(Some(path.clone()));
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    wait_for(&mut h, "the save", |app| !app.modified());
    h.run_steps(3);
    assert_eq!(
        h.state().project().large.depth,
        2.5,
        "no New after the later save"
    );
    assert_eq!(h.state().path(), Some(path.as_path()));
    // Now New asks nothing (saved); with a change, "Don't save" drops it.
    h.get_by_role_and_label(Role::Slider, "depth")
        .set_value_accesskit(2.5 + 0.5);
    settle(&mut h);
    menu(&mut h, "File", "New (default head)");
    h.get_by_role_and_label(Role::Button, "Don't save").click();
    settle(&mut h);
    assert_eq!(h.state().project().large.depth, 1.0);
    assert!(!h.state().modified());
}

#[test]
fn a_preset_applies_its_skin_and_undo_takes_it_back() {
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    let before = h.state().project().clone();
    menu(&mut h, "Presets", "goose-skin");
    settle(&mut h);
    let after = h.state().project().clone();
    assert_ne!(after.pores, before.pores);
    assert_eq!(
        after.large, before.large,
        "wrinkles are not part of a skin preset"
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(h.state().project().pores, before.pores);
    // The user's own preset: saved under a name, then listed in the menu.
    menu(&mut h, "Presets", "Save as preset…");
    h.get_by_role_and_label(Role::TextInput, "Name").click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::TextInput, "Name")
        .type_text("my skin");
    h.run_steps(2);
    h.get_by_role_and_label(Role::Button, "Save").click();
    let saved = dir.path().join("config/presets/my skin.agesim.json");
    wait_for(&mut h, "the preset file", |_| saved.is_file());
    h.run_steps(3);
    h.get_by_role_and_label(Role::Button, "Presets").click();
    // The menu lists the presets folder as read on a file thread: a few frames, more
    // when the machine is busy.
    let start = std::time::Instant::now();
    while h.query_by_label("my skin").is_none() {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(60),
            "the saved preset is not in the menu"
        );
        h.run_steps(1);
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

#[test]
fn an_export_cancelled_from_its_window_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    h.key_press_modifiers(Modifiers::COMMAND, Key::E);
    h.run_steps(2);
    dialogs.answer(Some(out.clone()));
    h.get_by_role_and_label(Role::Button, "Choose…").click();
    wait_for(&mut h, "the folder", |app| {
        app.export_settings().folder.as_deref() == Some(out.as_path())
    });
    let s = h.state_mut().export_settings_mut();
    s.size_px = 4096;
    s.height_exr = true;
    h.run_steps(2);
    h.get_by_role_and_label(Role::Button, "Export").click();
    h.run_steps(2);
    assert!(h.state().exporting(), "{:?}", h.state().open_errors());
    h.get_by_role_and_label(Role::Button, "Cancel").click();
    wait_for(&mut h, "the cancel", |app| !app.exporting());
    assert!(files_in(&out).is_empty(), "left: {:?}", files_in(&out));
    assert!(
        h.state().open_errors().is_empty(),
        "{:?}",
        h.state().open_errors()
    );
}

#[test]
fn the_glb_exported_from_the_window_loads_back() {
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    {
        let s = h.state_mut().export_settings_mut();
        s.folder = Some(dir.path().to_owned());
        s.base = "aged".into();
        s.size_px = 512;
        s.height_png = false;
        s.normal_png = false;
        s.glb = true;
        s.at_current_age = false;
        s.years = 72.0;
    }
    menu(&mut h, "File", "Export…");
    h.get_by_role_and_label(Role::Button, "Export").click();
    h.run_steps(2);
    wait_for(&mut h, "the export", |app| !app.exporting());
    assert!(
        h.state().open_errors().is_empty(),
        "{:?}",
        h.state().open_errors()
    );
    let (doc, _, images) = gltf::import(dir.path().join("aged.glb")).unwrap();
    let material = doc.materials().next().unwrap();
    assert!(material.name().unwrap().contains("72 years"));
    let normal = material.normal_texture().unwrap();
    assert_eq!(images[normal.texture().source().index()].width, 512);
    assert!(dir.path().join("aged_wrinkle_height.png").is_file());
}

/// A file dropped on the window, as the windowing integration hands it to egui.
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

#[test]
fn a_wrinkle_file_dropped_on_the_window_is_added_and_undo_removes_it() {
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    let fibres = fibre_count(&h);
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/wrinkles/thesis-forehead.wrk");
    let added = agesim_core::layers::wrinkles::wrinkle_file::load(&file)
        .unwrap()
        .groups
        .len();
    h.input_mut()
        .dropped_files
        .push(Arc::new(Dropped(file.clone())));
    wait_for(&mut h, "the dropped file", |app| {
        app.wrinkles().len() == agesim_core::defaults::WRINKLE_FILES.len() + 1
    });
    settle(&mut h);
    assert_eq!(fibre_count(&h), fibres + added);
    assert!(dialogs.asked().is_empty(), "a drop opens no dialog");
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(fibre_count(&h), fibres);
}

/// A head in centimetres dropped on the window is measured: its metres per unit are 0.01
/// (`mesh.metres_per_unit` = null, measured; taken for metres it asked for billions of
/// hairs and was refused), it gets the metres head's hair, and undo takes it back.
#[test]
fn a_head_in_centimetres_imported_is_measured_and_undo_takes_it_back() {
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let mut h = scripted(&dialogs, dir.path());
    let hairs_m = h.state().snapshot().hair.as_ref().unwrap().len();
    let mesh = dir.path().join("head-cm.obj");
    let head = agesim_core::head::default::default_head();
    std::fs::write(
        &mesh,
        agesim_core::head::mesh::obj::to_obj(&head, |p| p * 100.0),
    )
    .unwrap();
    h.input_mut()
        .dropped_files
        .push(Arc::new(Dropped(mesh.clone())));
    wait_for(&mut h, "the imported head", |app| {
        app.project().mesh.path.as_deref() == Some(mesh.as_path())
            && app.idle()
            && app.snapshot().layers.metres_per_unit == 0.01
    });
    assert_eq!(h.state().project().mesh.metres_per_unit, None);
    settle(&mut h);
    let hairs_cm = h.state().snapshot().hair.as_ref().unwrap().len();
    let ratio = hairs_cm as f64 / hairs_m as f64;
    assert!((0.98..1.02).contains(&ratio), "{hairs_cm} vs {hairs_m}");
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(h.state().project().mesh.path, None);
    assert_eq!(h.state().snapshot().layers.metres_per_unit, 1.0);
}

/// Where no native dialog can open (no XDG portal, no zenity: this machine under Xvfb),
/// File › Import head mesh… opens agesim's own file browser, says once why, and the
/// file typed there (its full path) is imported when Enter is pressed, as in any file
/// dialog.
#[test]
fn without_a_native_dialog_the_own_file_browser_imports_a_head() {
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::unavailable());
    let mut h = scripted(&dialogs, dir.path());
    let head = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/meshes/default-head.glb");
    menu(&mut h, "File", "Import head mesh");
    assert!(dialogs.asked().is_empty(), "no native dialog was tried");
    // The browser's window: type the head's path and open it.
    h.get_by_role_and_label(Role::TextInput, "file name")
        .click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::TextInput, "file name")
        .type_text(head.to_str().unwrap());
    h.run_steps(2);
    h.key_press(Key::Enter);
    wait_for(&mut h, "the imported head", |app| {
        app.project().mesh.path.as_deref() == Some(head.as_path()) && app.idle()
    });
    settle(&mut h);
    assert!(h.state().snapshot().hair.is_some());
}

/// A wrinkle file edited in a text editor while the project is open is read again: the
/// new fibres show (one undo step), a broken file keeps the fibres and says where it is
/// broken, and fixing it clears the error.
#[test]
fn a_wrinkle_file_changed_on_disk_is_reloaded() {
    let dir = tempfile::tempdir().unwrap();
    let wrk = dir.path().join("f.wrk");
    let group = |u: f32| format!("!\nma={u};0.5\nmb={};0.6\nn=3\n", u + 0.05);
    std::fs::write(&wrk, group(0.3)).unwrap();
    let project = dir.path().join("p.agesim.json");
    let mut p = agesim_core::project::Project::default();
    p.large.wrinkles = vec![wrk.clone()];
    p.save(&project).unwrap();
    let mut h = harness_with(EditorOptions {
        project: Some(project),
        ..EditorOptions::default()
    });
    settle(&mut h);
    assert_eq!(fibre_count(&h), 1);
    // A second group, as an artist would add it in a text editor.
    std::fs::write(&wrk, group(0.3) + &group(0.6)).unwrap();
    wait_for(&mut h, "the reload", |app| {
        app.wrinkles()
            .iter()
            .map(|w| w.file.groups.len())
            .sum::<usize>()
            == 2
            && app.idle()
    });
    settle(&mut h);
    assert_eq!(fibre_count(&h), 2);
    // Broken: the two fibres stay, the error names the file and the line.
    std::fs::write(&wrk, "!\nma=0.3;0.5\nmb=0.35;0.6\nn=0\n").unwrap();
    wait_for(&mut h, "the error", |app| {
        app.open_errors().iter().any(|e| e.contains("f.wrk:4:"))
    });
    assert_eq!(fibre_count(&h), 2);
    // Fixed: read again, the error gone.
    std::fs::write(&wrk, group(0.4)).unwrap();
    wait_for(&mut h, "the fixed file", |app| {
        app.open_errors().is_empty()
            && app
                .wrinkles()
                .iter()
                .map(|w| w.file.groups.len())
                .sum::<usize>()
                == 1
    });
    // Undo goes back to before the fix: the two fibres.
    settle(&mut h);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut h);
    assert_eq!(fibre_count(&h), 2);
}

/// An input image changed on disk (here the large-wrinkle mask) is read again by the next
/// bake, as one undo step (undo brings the content before back); one that no longer loads
/// keeps the previous one and says why; a good one again clears that.
#[test]
fn a_mask_changed_on_disk_is_reloaded_as_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let mask = dir.path().join("mask.png");
    let grey = |v: u8| image::GrayImage::from_pixel(64, 64, image::Luma([v]));
    grey(255).save(&mask).unwrap();
    let project = dir.path().join("p.agesim.json");
    let mut p = agesim_core::project::Project::default();
    p.large.mask = Some(mask.clone());
    // The wrinkles alone: the shape's relief, which the large map also carries, is not
    // the wrinkle mask's to hide.
    p.shape.enabled = false;
    p.save(&project).unwrap();
    let mut h = harness_with(EditorOptions {
        project: Some(project),
        ..EditorOptions::default()
    });
    settle(&mut h);
    let deepest = |h: &Harness<'static, EditorApp>| large_map(h).into_iter().fold(0.0, f32::max);
    // The deepest value of the large map the editor shows, once it has one.
    let shown_deepest =
        |app: &EditorApp| app.snapshot().large.as_ref().map(|l| l.height.min_max().1);
    assert!(deepest(&h) > 0.1);
    // Black: no large wrinkles anywhere.
    grey(0).save(&mask).unwrap();
    wait_for(&mut h, "the black mask", |app| {
        app.idle() && shown_deepest(app) == Some(0.0)
    });
    // The reload is one undo step: undone, the white mask is back as it was read (the
    // file on disk is black); redone, the black one.
    h.state_mut().undo();
    wait_for(&mut h, "the white mask again", |app| {
        app.idle() && shown_deepest(app).is_some_and(|d| d > 0.1)
    });
    h.state_mut().redo();
    wait_for(&mut h, "the black mask again", |app| {
        app.idle() && shown_deepest(app) == Some(0.0)
    });
    // Not an image: the black one stays, the message names the file.
    std::fs::write(&mask, b"not a png").unwrap();
    wait_for(&mut h, "the error", |app| {
        app.open_errors().iter().any(|e| e.contains("mask.png"))
    });
    settle(&mut h);
    assert_eq!(deepest(&h), 0.0);
    // White again: the wrinkles are back and the error is closed.
    grey(255).save(&mask).unwrap();
    wait_for(&mut h, "the white mask", |app| {
        app.idle() && app.open_errors().is_empty() && shown_deepest(app).is_some_and(|d| d > 0.1)
    });
}

/// The guided landmark mode on an imported head (the MakeHuman head, decimetres): its
/// landmarks found automatically show as labelled dots; a dot dragged moves over the
/// surface; a landmark picked in the list is placed by a click on the head; "Fit" writes
/// the landmark file beside the mesh, the project names it and the template is fitted
/// again from it.
#[test]
fn the_guided_landmark_mode_corrects_places_and_fits() {
    if !Path::new("/usr/share/vulkan/icd.d").exists() {
        return agesim_render::ci::skip_or_fail(
            "the_guided_landmark_mode_corrects_places_and_fits",
            "no Vulkan driver on this machine",
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let dialogs = Arc::new(ScriptedDialogs::default());
    let config = dir.path().join("config");
    // The 3D view needs the GPU device: a wgpu harness.
    let mut h = Harness::builder()
        .with_size([1280.0, 800.0])
        .wgpu()
        .build_eframe(move |cc| {
            EditorApp::new(
                cc,
                EditorOptions {
                    dialogs: Some(dialogs.clone()),
                    config_dir: Some(config.clone()),
                    ..EditorOptions::default()
                },
            )
        });
    settle(&mut h);
    let mesh = dir.path().join("mh_head.obj");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/heads/makehuman/mh_head.obj"),
        &mesh,
    )
    .unwrap();
    h.input_mut()
        .dropped_files
        .push(Arc::new(Dropped(mesh.clone())));
    wait_for(&mut h, "the imported head", |app| {
        app.project().mesh.path.as_deref() == Some(mesh.as_path()) && app.idle()
    });
    settle(&mut h);
    assert!(h.state().snapshot().landmarks_found);
    h.get_by_role_and_label(Role::Button, "landmarks").click();
    h.run_steps(3);
    assert!(h.state().landmark_mode().is_some(), "the mode is open");
    let dots = h.state().landmark_dots();
    assert_eq!(dots.len(), 16, "every landmark found is drawn: {dots:?}");
    // Drag an outer eye corner's dot a little: it moves down, over the head.
    let (_, at) = *dots.iter().find(|(n, _)| *n == "exocanthion_r").unwrap();
    let before = h
        .state()
        .landmark_mode()
        .unwrap()
        .points
        .get("exocanthion_r")
        .unwrap();
    drag(&mut h, at, at + egui::vec2(0.0, 12.0));
    h.run_steps(2);
    let mode = h.state().landmark_mode().unwrap();
    let after = mode.points.get("exocanthion_r").unwrap();
    assert!(mode.edited, "{dots:?}");
    assert!(after.distance(before) > 0.01, "{before} → {after} {dots:?}");
    assert!(after.y < before.y, "dragged down: {before} → {after}");
    // Pick "vertex" in the list and click on the head: the top of the head moves there.
    h.get_by_role_and_label(Role::Button, "vertex").click();
    h.run_steps(2);
    assert_eq!(h.state().landmark_mode().unwrap().selected, Some("vertex"));
    let forehead = dots.iter().find(|(n, _)| *n == "glabella").unwrap().1;
    // A press and release in place: a click.
    let above = forehead + egui::vec2(0.0, -30.0);
    h.hover_at(above);
    h.run_steps(1);
    h.drag_at(above);
    h.run_steps(1);
    h.drop_at(above);
    h.run_steps(3);
    let vertex = h
        .state()
        .landmark_mode()
        .unwrap()
        .points
        .get("vertex")
        .unwrap();
    let glabella = h
        .state()
        .landmark_mode()
        .unwrap()
        .points
        .get("glabella")
        .unwrap();
    assert!(vertex.y > glabella.y, "placed above the brows: {vertex}");
    h.get_by_role_and_label(Role::Button, "Fit").click();
    let written = dir.path().join("mh_head.landmarks.json");
    wait_for(&mut h, "the fit from the file", |app| {
        app.project().mesh.landmark_file() == Some(written.as_path()) && app.idle()
    });
    settle(&mut h);
    let file = agesim_core::head::landmarks::Landmarks::load(&written).unwrap();
    assert_eq!(file.len(), 16);
    assert!(!h.state().snapshot().landmarks_found);
    assert!(
        h.state().snapshot().layout_how.contains("landmark file"),
        "{}",
        h.state().snapshot().layout_how
    );
}

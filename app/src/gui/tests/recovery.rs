//! Headless UI tests (egui_kittest) of autosave and recovery: the recovery
//! file follows unsaved changes, a crashed run's file is offered on the next
//! start, and a clean close leaves nothing behind.

use super::{harness, seed_app, seed_path, step_shown};
use crate::gui::RaylabApp;
use crate::gui::doc::autosave::INTERVAL;
use crate::gui::doc::recovery;
use crate::gui::files::dialogs::DialogKind;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A process id Linux never gives (its largest is 2^22): a crashed run's.
const CRASHED: u32 = 999_999_999;

/// Lets the autosave's clock run past its interval.
fn advance_autosave(h: &mut Harness<'static, RaylabApp>) {
    let ctx = h.ctx.clone();
    let later = Instant::now() + INTERVAL + Duration::from_secs(1);
    h.state_mut().autosave_at(&ctx, later);
}

/// The files in `dir`.
fn files(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .map(|entries| entries.map(|e| e.expect("entry").path()).collect())
        .unwrap_or_default()
}

/// This run's recovery file in `dir`.
fn own_file(dir: &Path) -> PathBuf {
    recovery::file_of(dir, std::process::id())
}

#[test]
fn an_edit_is_autosaved_after_the_interval_and_reads_back_as_the_edited_scene() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32).with_recovery(dir.path()));
    h.step();
    advance_autosave(&mut h);
    assert_eq!(files(dir.path()), Vec::<PathBuf>::new(), "nothing unsaved");

    h.get_by_role_and_label(egui::accesskit::Role::Slider, "θ")
        .set_value_accesskit(37.0);
    h.step();
    assert!(h.state().doc.is_modified());
    assert!(!own_file(dir.path()).exists(), "not before the interval");
    advance_autosave(&mut h);
    assert_eq!(files(dir.path()), [own_file(dir.path())]);
    let (scene, source) = recovery::read(&own_file(dir.path())).expect("reads back");
    assert_eq!(scene.camera.theta_deg, 37.0);
    assert_eq!(scene, h.state().doc.state.scene);
    assert_eq!(source.as_deref(), Some(seed_path().as_path()));
}

#[test]
fn saving_removes_the_recovery_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scenes = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32).with_recovery(dir.path()));
    h.state_mut().doc.state.scene.camera.theta_deg = 29.0;
    h.step();
    advance_autosave(&mut h);
    assert!(own_file(dir.path()).exists());
    let ctx = h.ctx.clone();
    h.state_mut()
        .chosen(&ctx, DialogKind::SaveScene, scenes.path().join("s.xml"));
    h.step();
    assert!(!own_file(dir.path()).exists());
}

/// A harness started with a crashed run's recovery file of the seed scene
/// at θ = 27° in `dir`; returns it and the recovered scene.
fn started_after_a_crash(dir: &Path) -> (Harness<'static, RaylabApp>, scene::Scene) {
    let mut edited = seed_app(48, 32).doc.state.scene;
    edited.camera.theta_deg = 27.0;
    recovery::write(
        &recovery::file_of(dir, CRASHED),
        &edited,
        Some(&seed_path()),
    )
    .expect("written");
    let mut h = harness(seed_app(48, 32).with_recovery(dir));
    step_shown(&mut h);
    h.get_by_label("Restore unsaved work?");
    h.get_by_label_contains("seed.xml");
    // The age is unit-tested in recovery.rs; here only that it is shown
    // (a loaded machine may take over a second to get this far).
    h.get_by_label_contains(" s ago");
    (h, edited)
}

#[test]
fn restoring_a_crashed_runs_work_opens_it_unsaved_with_its_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (mut h, edited) = started_after_a_crash(dir.path());
    h.get_by_label("Restore").click();
    step_shown(&mut h);
    assert!(h.query_by_label("Restore unsaved work?").is_none());
    assert_eq!(h.state().doc.state.scene, edited);
    assert_eq!(h.state().doc.path.as_deref(), Some(seed_path().as_path()));
    assert!(h.state().doc.title().starts_with("• seed.xml"));
    // The crashed run's file became this run's: the work stays on disk.
    assert_eq!(files(dir.path()), [own_file(dir.path())]);
}

#[test]
fn discarding_a_crashed_runs_work_deletes_its_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (mut h, _) = started_after_a_crash(dir.path());
    h.get_by_label("Discard").click();
    step_shown(&mut h);
    assert!(h.query_by_label("Restore unsaved work?").is_none());
    assert_eq!(files(dir.path()), Vec::<PathBuf>::new());
    assert!(!h.state().doc.is_modified());
    assert_eq!(h.state().doc.state.scene, seed_app(48, 32).doc.state.scene);
}

#[test]
fn closing_without_saving_removes_the_recovery_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32).with_recovery(dir.path()));
    h.state_mut().doc.state.scene.objects.pop();
    h.step();
    advance_autosave(&mut h);
    assert!(own_file(dir.path()).exists());
    h.state_mut().files.guard = Some(crate::gui::files::Pending::Close);
    step_shown(&mut h);
    h.get_by_label("Don't save").click();
    h.step();
    assert!(h.state().files.allow_close);
    eframe::App::on_exit(h.state_mut());
    assert_eq!(files(dir.path()), Vec::<PathBuf>::new());
}

#[test]
fn an_exit_forced_past_unsaved_changes_keeps_the_recovery_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32).with_recovery(dir.path()));
    h.state_mut().doc.state.scene.objects.pop();
    h.step();
    advance_autosave(&mut h);
    eframe::App::on_exit(h.state_mut());
    assert_eq!(files(dir.path()), [own_file(dir.path())]);
}

#[test]
fn a_failed_save_says_so_and_keeps_the_unsaved_mark() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32));
    h.state_mut().doc.state.scene.camera.theta_deg = 22.0;
    h.step();
    let ctx = h.ctx.clone();
    let path = dir.path().join("no-such-folder").join("s.xml");
    h.state_mut().chosen(&ctx, DialogKind::SaveScene, path);
    step_shown(&mut h);
    h.get_by_label_contains("The file on disk is unchanged");
    assert!(h.state().doc.title().starts_with("• seed.xml"));
    assert_eq!(h.state().doc.path.as_deref(), Some(seed_path().as_path()));
}

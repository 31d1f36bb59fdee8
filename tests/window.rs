//! End to end: the real `raylab` window under Xvfb with Mesa's software
//! Vulkan. Screenshots of the whole screen are taken every second until one
//! shows the rendered seed scene (the red sphere in the image area) beside the
//! camera panel; that screenshot is kept in target/tmp/ for a person to look at.

mod support;

use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::time::{Duration, Instant};

/// The xvfb-run process. Dropping it asks the script to close raylab (by
/// creating the stop file) and waits for xvfb-run to end by itself, which
/// takes Xvfb down with it. Nothing here signals a process group.
struct Session {
    child: Child,
    stop: PathBuf,
}

impl Drop for Session {
    fn drop(&mut self) {
        let _ = std::fs::write(&self.stop, b"");
        let deadline = Instant::now() + Duration::from_secs(30);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// True when the screenshot shows the seed scene's red sphere right of the
/// panel and light panel text left of it.
fn shows_scene_and_panel(img: &image::RgbImage) -> bool {
    let (w, h) = img.dimensions();
    let red = img
        .enumerate_pixels()
        .filter(|(x, _, p)| *x > w / 4 && p[0] > 180 && p[1] < 60 && p[2] < 60)
        .count();
    let text = (0..w / 4)
        .flat_map(|x| (0..h / 2).map(move |y| (x, y)))
        .filter(|&(x, y)| img.get_pixel(x, y).0.iter().all(|&c| c > 150))
        .count();
    red > 2000 && text > 200
}

/// Starts `script` under xvfb-run (1280×800) with raylab on the seed scene:
/// `$RAYLAB`, `$SCENE`, `$SHOT` (dir/shot.png), `$STOP` (dir/stop) and the
/// `extra` variables are set; the XDG folders (runtime, persistence and so
/// recovery files) are inside `dir`, never the user's.
fn start_in_xvfb(dir: &Path, script: &str, extra: &[(&str, &Path)]) -> Session {
    let runtime = dir.join("xdg");
    std::fs::create_dir(&runtime).expect("runtime dir");
    std::fs::set_permissions(
        &runtime,
        std::os::unix::fs::PermissionsExt::from_mode(0o700),
    )
    .expect("chmod");
    let stop = dir.join("stop");
    let child = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", "bash", "-c", script])
        .env("RAYLAB", env!("CARGO_BIN_EXE_raylab"))
        .env("SCENE", support::asset("seed.xml"))
        .env("SHOT", dir.join("shot.png"))
        .env("STOP", &stop)
        .envs(extra.iter().copied())
        .env("XDG_RUNTIME_DIR", &runtime)
        // Persistence (recent files, window layout) goes to the temp dir, not the user's.
        .env("XDG_DATA_HOME", dir)
        // Recovery files then live under XDG_DATA_HOME too: none to offer.
        .env_remove("RAYLAB_RECOVERY_DIR")
        .env("WGPU_BACKEND", "vulkan")
        .spawn()
        .expect("xvfb-run starts (scripts/setup.sh installs it)");
    Session { child, stop }
}

/// Keeps a screenshot under target/tmp/ and returns its path.
fn keep(img: &image::RgbImage, name: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    img.save(&path).expect("keep the screenshot");
    path
}

#[test]
fn window_shows_the_rendered_seed_scene_beside_the_camera_panel() {
    let dir = tempfile::tempdir().expect("tempdir");
    let shot = dir.path().join("shot.png");
    let script = r#"
        "$RAYLAB" "$SCENE" & pid=$!
        while kill -0 $pid 2>/dev/null && [ ! -e "$STOP" ]; do
          sleep 1
          import -window root "$SHOT.tmp.png" 2>/dev/null && mv "$SHOT.tmp.png" "$SHOT"
        done
        kill $pid 2>/dev/null
        wait $pid
        exit 0"#;
    let mut session = start_in_xvfb(dir.path(), script, &[]);

    let deadline = Instant::now() + Duration::from_secs(120);
    let mut last = None;
    while Instant::now() < deadline {
        if let Ok(Some(status)) = session.child.try_wait() {
            panic!("the window exited early with {status}");
        }
        if let Ok(img) = image::open(&shot).map(|i| i.to_rgb8()) {
            if shows_scene_and_panel(&img) {
                println!("screenshot: {}", keep(&img, "window.png").display());
                return;
            }
            last = Some(img);
        }
        std::thread::sleep(Duration::from_millis(500));
    }
    drop(session);
    let kept = last.map(|img| keep(&img, "window-failed.png"));
    panic!("no screenshot showed the rendered scene within 120 s; the last: {kept:?}");
}

#[test]
fn the_window_resized_continuously_mid_render_then_closed_with_ctrl_q_exits_cleanly() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (shot, status) = (dir.path().join("shot.png"), dir.path().join("status"));
    // Resizes the window 150 times while the seed scene refines toward 64 spp,
    // takes a screenshot, closes it with Ctrl+Q and records raylab's exit status.
    let script = r#"
        command -v xdotool >/dev/null || { echo "no xdotool (scripts/setup.sh installs it)" > "$STATUS"; exit 0; }
        "$RAYLAB" "$SCENE" & pid=$!
        wid=
        for i in $(seq 120); do
          wid=$(xdotool search --name raylab 2>/dev/null | head -1)
          [ -n "$wid" ] && break
          sleep 0.5
        done
        [ -n "$wid" ] || { echo nowindow > "$STATUS"; kill $pid; exit 0; }
        sleep 2
        for i in $(seq 150); do
          xdotool windowsize "$wid" $((320 + i * 37 % 900)) $((240 + i * 53 % 520)) 2>/dev/null
          sleep 0.02
        done
        xdotool windowsize "$wid" 1280 800
        sleep 3
        import -window root "$SHOT.tmp.png" 2>/dev/null && mv "$SHOT.tmp.png" "$SHOT"
        xdotool windowfocus --sync "$wid" key ctrl+q
        for i in $(seq 300); do kill -0 $pid 2>/dev/null || break; [ -e "$STOP" ] && break; sleep 0.1; done
        if kill -0 $pid 2>/dev/null; then echo stuck > "$STATUS"; kill $pid; wait $pid; exit 0; fi
        wait $pid
        echo "exit $?" > "$STATUS"
        exit 0"#;
    let mut session = start_in_xvfb(dir.path(), script, &[("STATUS", &status)]);
    let deadline = Instant::now() + Duration::from_secs(180);
    while Instant::now() < deadline && !status.exists() {
        std::thread::sleep(Duration::from_millis(200));
    }
    let _ = session.child.wait();
    let status = std::fs::read_to_string(&status).unwrap_or_else(|_| "no status".into());
    let img = image::open(&shot).map(|i| i.to_rgb8());
    if let Ok(img) = &img {
        println!("screenshot: {}", keep(img, "window-resized.png").display());
    }
    assert_eq!(
        status.trim(),
        "exit 0",
        "raylab did not exit cleanly after Ctrl+Q"
    );
    let img = img.expect("a screenshot after the resizing");
    assert!(
        shows_scene_and_panel(&img),
        "after the resizing the window does not show the scene beside the panel"
    );
}

//! End-to-end tests of `raylab render`: the real binary on real files.

mod support;

use support::{asset, raylab, raylab_ok, read_png, render};

#[test]
fn every_shipped_scene_renders_to_a_lit_png() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scenes = [
        "seed.xml",
        "primitives.xml",
        "cornell.xml",
        "glass.xml",
        "roughness.xml",
    ];
    for name in scenes {
        let out = dir.path().join(name.replace(".xml", ".png"));
        let output = render(
            &asset(name),
            &out,
            &["--width", "64", "--height", "48", "--spp", "2"],
        );
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(
            stdout.contains(out.to_str().expect("utf-8")),
            "prints the output path: {stdout}"
        );
        assert!(stdout.contains(" s"), "prints the render time: {stdout}");
        let img = read_png(&out);
        assert_eq!(img.dimensions(), (64, 48));
        let lit = img.pixels().filter(|p| p.0.iter().any(|&c| c > 40)).count();
        assert!(
            lit > 64 * 48 / 4,
            "{name}: most of the image is lit ({lit} pixels)"
        );
    }
}

#[test]
fn malformed_scene_reports_file_line_and_column_with_exit_code_2() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("bad.xml");
    std::fs::write(&scene, "<scene>\n  <sphere radius=\"-1\"/>\n</scene>\n").expect("write");
    let out = dir.path().join("bad.png");
    let output = raylab(&[
        "render",
        scene.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    let place = format!("{}:2:", scene.display());
    assert!(
        stderr.contains(&place) && stderr.contains("radius"),
        "{stderr}"
    );
    assert!(!out.exists(), "no image is written for a bad scene");
}

#[test]
fn missing_scene_file_and_unknown_format_are_clear_errors() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("x.png");
    let output = raylab(&[
        "render",
        "/nonexistent/scene.xml",
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("/nonexistent/scene.xml"));

    let bmp = dir.path().join("x.bmp");
    let output = raylab(&[
        "render",
        asset("seed.xml").to_str().expect("utf-8"),
        "-o",
        bmp.to_str().expect("utf-8"),
    ]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains(".png or .exr"));
}

#[test]
fn image_is_independent_of_view_window_distance() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut images = Vec::new();
    for d in ["0.001", "1", "1000"] {
        let scene = dir.path().join(format!("d{d}.xml"));
        std::fs::write(
            &scene,
            format!(
                r#"<scene>
  <camera eye="0 2 7" toward="0 -0.25 -1" theta="25" d="{d}" width="96" height="64"/>
  <sphere center="-1.2 1 0" radius="1" color="red"/>
  <box center="1.3 0.75 0" size="1.5 1.5 1.5" rotate="0 30 0" color="purple"/>
  <floor material="marble"/>
</scene>"#
            ),
        )
        .expect("write");
        let out = dir.path().join(format!("d{d}.png"));
        render(&scene, &out, &["--spp", "2"]);
        images.push(read_png(&out));
    }
    for other in &images[1..] {
        // v_ij is formed in f64, where d's rounding is far below f32 precision.
        assert!(images[0].as_raw() == other.as_raw(), "d changes no pixel");
    }
}

#[test]
fn image_is_identical_for_any_thread_count() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut bytes = Vec::new();
    for threads in ["1", "2"] {
        let out = dir.path().join(format!("t{threads}.png"));
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
            .env("RAYON_NUM_THREADS", threads)
            .args([
                "render",
                asset("glass.xml").to_str().expect("utf-8"),
                "-o",
                out.to_str().expect("utf-8"),
            ])
            .args(["--width", "80", "--height", "50", "--spp", "3"])
            .output()
            .expect("runs");
        assert!(output.status.success());
        bytes.push(read_png(&out).into_raw());
    }
    assert!(bytes[0] == bytes[1], "1 and 2 threads give the same pixels");
}

#[test]
fn depth_exr_has_one_z_channel_with_infinite_misses() {
    use exr::prelude::*;
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("one-sphere.xml");
    std::fs::write(
        &scene,
        r#"<scene><camera eye="0 0 5" toward="0 0 -1" theta="30" width="32" height="32"/><sphere center="0 0 0" radius="1"/></scene>"#,
    )
    .expect("write");
    let out = dir.path().join("depth.exr");
    render(&scene, &out, &["--aov", "depth"]);
    let image = read_all_flat_layers_from_file(&out).expect("reads");
    let layer = &image.layer_data[0];
    let names: Vec<String> = layer
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    assert_eq!(names, ["Z"]);
    let z: Vec<f32> = layer.channel_data.list[0]
        .sample_data
        .values_as_f32()
        .collect();
    let centre = z[16 * 32 + 16];
    // The ray through the pixel centre next to the image centre hits the sphere near α = 4.
    assert!((centre - 4.0).abs() < 0.01, "{centre}");
    assert!(z[0].is_infinite(), "a corner ray misses: {}", z[0]);
}

#[test]
fn lecture_method_renders_a_well_conditioned_scene_like_the_robust_one() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut images = Vec::new();
    for method in ["lecture", "robust"] {
        let out = dir.path().join(format!("{method}.png"));
        render(
            &asset("primitives.xml"),
            &out,
            &[
                "--width", "96", "--height", "60", "--spp", "2", "--method", method,
            ],
        );
        images.push(read_png(&out));
    }
    let differing = images[0]
        .pixels()
        .zip(images[1].pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0.iter()).any(|(x, y)| x.abs_diff(*y) > 2))
        .count();
    // Only pixels where rounding flips a silhouette or shadow edge may differ.
    assert!(differing < 96 * 60 / 100, "{differing} pixels differ");
}

/// Runs `raylab bench ARGS` and checks that it succeeds and prints every figure.
fn assert_bench_prints(args: &[&str], figures: &[&str]) {
    let stdout = raylab_ok(&[&["bench"], args].concat());
    for figure in figures {
        assert!(stdout.contains(figure), "missing {figure:?} in {stdout}");
    }
}

#[test]
fn bench_interactive_reports_latency_and_ui_frame_time() {
    assert_bench_prints(
        &[
            "interactive",
            "--width",
            "64",
            "--height",
            "48",
            "--edits",
            "2",
        ],
        &[
            "edit → first preview on screen",
            "edit → first full pass on screen",
            "UI frame time while rendering",
        ],
    );
}

#[test]
fn bench_debug_view_draws_whole_frames_on_the_software_adapter() {
    assert_bench_prints(
        &[
            "debug-view",
            "--width",
            "64",
            "--height",
            "48",
            "--frames",
            "3",
        ],
        &[
            "UI thread per frame",
            "whole frame, GPU finished",
            "3 frames",
        ],
    );
}

/// The text chunks (keyword, text) of the PNG at `path`.
fn png_text(path: &std::path::Path) -> Vec<(String, String)> {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(path).expect("the PNG exists"),
    ));
    let reader = decoder.read_info().expect("a PNG");
    reader
        .info()
        .utf8_text
        .iter()
        .map(|c| (c.keyword.clone(), c.get_text().expect("utf-8")))
        .collect()
}

#[test]
fn ctrl_c_stops_a_render_after_its_pass_and_writes_the_passes_done() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("seed.png");
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(["render", asset("seed.xml").to_str().expect("utf-8")])
        .args([
            "--width", "32", "--height", "24", "--spp", "65536", "--output",
        ])
        .arg(&out)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("raylab starts");
    // 65,536 passes would take minutes; after a few seconds, Ctrl+C.
    std::thread::sleep(std::time::Duration::from_secs(3));
    // The shell's own `kill` (procps' /bin/kill may be missing on a clean machine).
    let kill = std::process::Command::new("sh")
        .args(["-c", &format!("kill -INT {}", child.id())])
        .status()
        .expect("sh runs");
    assert!(kill.success());
    let output = child.wait_with_output().expect("raylab ends");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{:?}\n{stdout}{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    // "wrote …/seed.png in 2.9 s (stopped by Ctrl+C: N of 65536 passes)"
    let passes: u32 = stdout
        .split("stopped by Ctrl+C: ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("the report says how many passes were done: {stdout}"));
    assert!(
        passes >= 1 && stdout.contains("of 65536 passes"),
        "{stdout}"
    );
    // The image holds those passes, and says so.
    let spp = png_text(&out)
        .into_iter()
        .find(|(key, _)| key == "raylab:spp")
        .map(|(_, value)| value);
    assert_eq!(spp, Some(passes.to_string()));
}

#[test]
fn a_render_on_a_terminal_shows_its_passes_done_and_the_time_left() {
    // `script` (util-linux, in every Debian) runs raylab on a
    // pseudo-terminal, as a person would at a shell.
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("seed.png");
    let command = format!(
        "'{}' render '{}' --width 32 --height 24 --spp 400 -o '{}'",
        env!("CARGO_BIN_EXE_raylab"),
        asset("seed.xml").display(),
        out.display()
    );
    let output = std::process::Command::new("script")
        .args(["-q", "-e", "-c", &command, "/dev/null"])
        .output()
        .expect("script runs");
    let shown = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{shown}");
    assert!(
        shown.contains("/400 passes") && shown.contains("elapsed") && shown.contains("left"),
        "{shown}"
    );
    assert!(shown.contains("wrote"), "{shown}");
}

#[test]
fn a_render_whose_stderr_is_not_a_terminal_prints_no_progress() {
    // Progress is drawn for a person at a terminal; a pipe or a log gets
    // only the report.
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("seed.png");
    let output = render(
        &asset("seed.xml"),
        &out,
        &["--width", "32", "--height", "24", "--spp", "8"],
    );
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn rendered_png_records_the_camera_and_the_scene_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("seed.png");
    render(
        &asset("seed.xml"),
        &out,
        &["--width", "32", "--height", "24", "--spp", "1"],
    );
    let text = png_text(&out);
    let get = |k: &str| {
        text.iter()
            .find(|(key, _)| key == k)
            .map(|(_, v)| v.as_str())
    };
    assert!(
        get("raylab:camera").is_some_and(|c| c.contains("w=32 h=24")),
        "{text:?}"
    );
    assert!(
        get("raylab:scene").is_some_and(|s| s.ends_with("seed.xml")),
        "{text:?}"
    );
    assert_eq!(get("raylab:spp"), Some("1"));
}

/// Runs `raylab inspect` with `args`, requires success and parses its JSON.
fn inspect_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["inspect"];
    all.extend_from_slice(args);
    let stdout = raylab_ok(&all);
    serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("stdout is not JSON ({e}):\n{stdout}"))
}

fn vec3(value: &serde_json::Value) -> [f64; 3] {
    let a = value.as_array().expect("a vector is a JSON array");
    assert_eq!(a.len(), 3, "{value}");
    [0, 1, 2].map(|k| a[k].as_f64().expect("a number"))
}

#[test]
fn inspect_prints_the_ray_tree_of_the_centre_pixel_of_seed_as_json() {
    // seed.xml places its cone, sphere and box side by side in document
    // order on the floor, and the default camera frames them about their
    // middle: the centre of the image sees the sphere, object 1.
    let seed = asset("seed.xml");
    let json = inspect_json(&[
        seed.to_str().expect("utf-8"),
        "--pixel",
        "16",
        "10",
        "--width",
        "32",
        "--height",
        "20",
    ]);
    assert_eq!(
        (json["i"].as_u64(), json["j"].as_u64()),
        (Some(16), Some(10))
    );
    assert!(json["sample"].is_null(), "the centre ray: no sample index");
    let v = vec3(&json["v_ij"]);
    let length = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!((length - 1.0).abs() < 1e-6, "v_ij is a unit vector: {v:?}");
    assert_eq!(vec3(&json["p_ij"]), vec3(&json["window_point"]));

    let rays = json["rays"].as_array().expect("rays");
    let primary = &rays[0];
    assert_eq!(primary["kind"], "primary");
    assert!(primary["parent"].is_null());
    assert_eq!(vec3(&primary["direction"]), v);
    assert_eq!(primary["object"]["index"], 1, "{primary}");
    assert!(
        primary["object"]["name"]
            .as_str()
            .is_some_and(|n| n.starts_with("sphere")),
        "{primary}"
    );
    assert_eq!(primary["shape"], "sphere");
    let alpha = primary["alpha"].as_f64().expect("α");
    assert_eq!(primary["sphere"]["roots"]["near"].as_f64(), Some(alpha));
    for key in ["point", "normal", "origin", "contribution", "weight"] {
        vec3(&primary[key]);
    }
    assert!(
        rays.iter()
            .any(|r| r["kind"] == "shadow" && r["parent"] == 0 && r["light"].is_u64()),
        "the sphere's hit casts shadow rays: {json}"
    );

    // The contributions add up to the colour.
    let color = vec3(&json["color"]);
    let mut sum = [0.0; 3];
    for ray in rays {
        let c = vec3(&ray["contribution"]);
        (0..3).for_each(|k| sum[k] += c[k]);
    }
    for k in 0..3 {
        assert!(
            (sum[k] - color[k]).abs() <= 1e-5 * color[k].abs() + 1e-12,
            "{sum:?} vs {color:?}"
        );
    }
}

#[test]
fn inspected_sample_zero_equals_the_pixel_of_a_one_sample_render() {
    use exr::prelude::*;
    let dir = tempfile::tempdir().expect("tempdir");
    let size = ["--width", "40", "--height", "25"];
    for (scene, integrator) in [("glass.xml", "whitted"), ("cornell.xml", "path")] {
        let out = dir.path().join(format!("{scene}.exr"));
        let mut args = vec!["--spp", "1", "--seed", "11", "--integrator", integrator];
        args.extend_from_slice(&size);
        render(&asset(scene), &out, &args);
        let image = read_all_flat_layers_from_file(&out).expect("reads");
        let channels: Vec<Vec<f32>> = image.layer_data[0]
            .channel_data
            .list
            .iter()
            .map(|c| c.sample_data.values_as_f32().collect())
            .collect();
        let path = asset(scene);
        let mut bounces = 0;
        for (i, j) in [(9usize, 15usize), (20, 12), (33, 18)] {
            let (si, sj) = (i.to_string(), j.to_string());
            let mut args = vec![path.to_str().expect("utf-8"), "--pixel", &si, &sj];
            args.extend_from_slice(&["--sample", "0", "--seed", "11", "--integrator", integrator]);
            args.extend_from_slice(&size);
            let json = inspect_json(&args);
            assert_eq!(
                (&json["sample"], &json["integrator"]),
                (&0.into(), &integrator.into())
            );
            // JSON prints each f32 in its shortest round-tripping form.
            let color = vec3(&json["color"]).map(|x| x as f32);
            // EXR channels are stored alphabetically: B, G, R.
            let pixel = [2, 1, 0].map(|c| channels[c][j * 40 + i]);
            assert_eq!(color, pixel, "{scene} {integrator}: pixel ({i}, {j})");
            let rays = json["rays"].as_array().expect("rays");
            bounces += rays
                .iter()
                .filter(|r| r["scatter"]["lobe"].is_string())
                .count();
            for shadow in rays.iter().filter(|r| r["kind"] == "shadow") {
                assert!(
                    shadow["light"].is_u64() || shadow["emitter"]["pdf"].is_f64(),
                    "{shadow}"
                );
            }
        }
        // A path-traced sample records the BSDF sample of each bounce.
        assert_eq!(bounces > 0, integrator == "path", "{scene} {integrator}");
    }
}

#[test]
fn a_reader_that_closes_the_pipe_first_ends_raylab_quietly_not_in_a_panic() {
    // `raylab inspect … | head -c 0`: the pipe is closed before raylab has
    // traced the pixel and written its JSON (a Unix tool ends quietly there;
    // `println!` would panic with exit code 101).
    let seed = asset("seed.xml");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args([
            "inspect",
            seed.to_str().expect("utf-8"),
            "--pixel",
            "16",
            "10",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("raylab starts");
    drop(child.stdout.take());
    let output = child.wait_with_output().expect("raylab ends");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success() && !stderr.contains("panicked"),
        "{:?}\n{stderr}",
        output.status
    );
}

#[test]
fn inspect_of_a_pixel_outside_the_image_names_the_valid_range() {
    let output = raylab(&[
        "inspect",
        asset("seed.xml").to_str().expect("utf-8"),
        "--pixel",
        "32",
        "5",
        "--width",
        "32",
        "--height",
        "20",
    ]);
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("(32, 5)")
            && stderr.contains("32×20")
            && stderr.contains("0..=31")
            && stderr.contains("0..=19"),
        "{stderr}"
    );
    assert!(output.stdout.is_empty(), "no JSON for a refused pixel");
}

#[test]
fn cost_exr_counts_only_the_shape_tests_the_bvh_makes() {
    use exr::prelude::*;
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("two-spheres.xml");
    // A lit sphere in view and a second one far off to the side: N = 2.
    std::fs::write(
        &scene,
        r#"<scene><camera eye="0 0 5" toward="0 0 -1" theta="30" width="16" height="16"/>
           <light type="point" position="0 0 10" intensity="50"/>
           <sphere center="0 0 0" radius="1"/><sphere center="100 0 0" radius="1"/></scene>"#,
    )
    .expect("write");
    let out = dir.path().join("cost.exr");
    // Ray by ray through the BVH: the lecture's formulas take no packets.
    render(
        &scene,
        &out,
        &["--aov", "cost", "--spp", "2", "--method", "lecture"],
    );
    let image = read_all_flat_layers_from_file(&out).expect("reads");
    let channel = &image.layer_data[0].channel_data.list[0];
    assert_eq!(channel.name.to_string(), "cost");
    let cost: Vec<f32> = channel.sample_data.values_as_f32().collect();
    // The BVH tests a shape only when the ray enters its box.
    assert_eq!(cost[0], 0.0, "a corner ray enters no box: no shape test");
    assert_eq!(
        cost[8 * 16 + 8],
        2.0,
        "a lit hit: the sphere in view, then again for the shadow ray; never the far one"
    );
}

#[test]
fn bench_on_a_generated_mesh_reports_build_throughput_memory_and_frame_time_as_json() {
    let stdout = raylab_ok(&[
        "bench",
        "knot:2000",
        "--width",
        "64",
        "--height",
        "36",
        "--json",
    ]);
    let f: serde_json::Value = serde_json::from_str(&stdout).expect("JSON");
    assert_eq!(
        f["triangles"], 2004,
        "the knot's 2000 and the floor square's 4"
    );
    assert_eq!(f["width"], 64);
    for cast in ["primary", "incoherent"] {
        for threads in ["one", "all"] {
            let c = &f[cast][threads];
            assert_eq!(c["rays"], 64 * 36, "{cast} {threads}");
            let hit = c["hit_fraction"].as_f64().expect("hit fraction");
            assert!(hit > 0.05 && hit < 1.0, "{cast} {threads}: {hit}");
            assert!(c["mrays_per_second"].as_f64().expect("rate") > 0.0);
            // Batches (packets, interleaved rays) hit exactly the same rays.
            let batched = &f[format!("{cast}_batched")][threads];
            assert_eq!(
                batched["hit_fraction"], c["hit_fraction"],
                "{cast} {threads}"
            );
            assert!(batched["mrays_per_second"].as_f64().expect("rate") > 0.0);
        }
    }
    assert!(f["bytes_per_triangle"].as_f64().expect("bytes") >= 36.0);
    assert!(f["mesh_bvh_build_seconds"].as_f64().expect("build") > 0.0);
    assert!(
        f["mesh_bvh_build_seconds_one_thread"]
            .as_f64()
            .expect("build on 1 thread")
            > 0.0
    );
    assert!(f["whitted_frame_seconds"]["one"].as_f64().expect("frame") > 0.0);
}

#[test]
fn bench_names_the_scene_it_cannot_read() {
    let output = raylab(&["bench", "no-such-scene.xml"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("no-such-scene.xml"), "{stderr}");
}

#[test]
fn bench_export_writes_files_whose_sizes_agree_with_its_manifest() {
    let dir = tempfile::tempdir().expect("tempdir");
    let export = dir.path().join("knot");
    let stdout = raylab_ok(&[
        "bench",
        "knot:240",
        "--width",
        "16",
        "--height",
        "9",
        "--json",
        "--export",
        export.to_str().expect("utf-8"),
    ]);
    let text = std::fs::read_to_string(export.join("manifest.json")).expect("manifest");
    let m: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let count = |v: &serde_json::Value| v.as_u64().expect("a count");
    let size = |name: &serde_json::Value| {
        std::fs::metadata(export.join(name.as_str().expect("a file name")))
            .expect("exported file")
            .len()
    };
    let (vertices, triangles) = (count(&m["vertices"]), count(&m["triangles"]));
    assert_eq!(size(&m["vertices_file"]), 12 * vertices);
    assert_eq!(size(&m["triangles_file"]), 12 * triangles);
    for rays in ["primary", "incoherent"] {
        assert_eq!(count(&m[rays]["count"]), 16 * 9, "{rays}");
        assert_eq!(size(&m[rays]["file"]), 24 * 16 * 9, "{rays}");
    }
    // The knot and its floor square of 4 triangles, in contiguous ranges
    // (an infinite plane's square is covered by bench_export's unit tests).
    let geometries = m["geometries"].as_array().expect("geometries");
    assert_eq!(geometries.len(), 2);
    assert_eq!(geometries[0]["kind"], "mesh");
    assert_eq!(count(&geometries[0]["triangles"]), 240);
    assert_eq!(geometries[1]["kind"], "mesh");
    assert_eq!(count(&geometries[1]["triangles"]), 4);
    assert_eq!(count(&geometries[1]["first_triangle"]), 240);
    assert_eq!(
        count(&geometries[1]["first_vertex"]) + count(&geometries[1]["vertices"]),
        vertices
    );
    let bytes = std::fs::read(export.join("triangles.u32")).expect("triangles");
    assert!(
        bytes
            .chunks_exact(4)
            .all(|b| u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])) < vertices),
        "every index names a vertex"
    );
    // raylab's own figures on the same rays, from the same process.
    assert_eq!(m["raylab"]["primary"]["all"]["rays"], 16 * 9);
    assert!(m["raylab"]["incoherent"]["all"]["hit_fraction"].as_f64() > Some(0.0));
    let printed: serde_json::Value = serde_json::from_str(&stdout).expect("JSON");
    assert_eq!(printed["triangles"], 244, "the figures are still printed");
}

#[test]
fn bench_export_is_refused_for_the_window_benchmarks() {
    let dir = tempfile::tempdir().expect("tempdir");
    let output = raylab(&[
        "bench",
        "interactive",
        "--export",
        dir.path().to_str().expect("utf-8"),
    ]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("--export"));
}

#[test]
fn chart_writes_error_against_time_per_method_as_csv_and_a_png() {
    let dir = tempfile::tempdir().expect("tempdir");
    // The lamp is just above the frame: a lamp in view would put its edge
    // in a few pixels whose error leaps whenever a sample lands on it, and
    // the curve would fall or not by luck.
    let scene = dir.path().join("lamp.xml");
    std::fs::write(
        &scene,
        r#"<scene>
  <camera eye="0 1 4" toward="0 -0.2 -1" theta="20" width="24" height="16"/>
  <sphere center="0 0.5 0" radius="0.5" color="0.7 0.6 0.5"/>
  <triangle t0="-1 0 1" t1="1 0 1" t2="1 0 -1" color="0.5 0.5 0.5"/>
  <triangle t0="-1 0 1" t1="1 0 -1" t2="-1 0 -1" color="0.5 0.5 0.5"/>
  <triangle t0="-0.5 2 -0.5" t1="0.5 2 -0.5" t2="0.5 2 0.5" emission="4 4 4"/>
</scene>"#,
    )
    .expect("write");
    let prefix = dir.path().join("lamp-chart");
    let stdout = raylab_ok(&[
        "chart",
        scene.to_str().expect("utf-8"),
        "--methods",
        "path,whitted,path-sobol,path-adaptive",
        "--seconds",
        "0.5",
        "--max-spp",
        "16",
        "-o",
        prefix.to_str().expect("utf-8"),
    ]);
    assert!(stdout.contains("to 1e-2"), "prints time to 1e-2: {stdout}");
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).expect("csv written");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("method,spp,mean_spp,seconds,rel_mse,rmse,flip")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    for method in ["path", "whitted", "path-sobol", "path-adaptive"] {
        let mine: Vec<&Vec<&str>> = rows.iter().filter(|r| r[0] == method).collect();
        assert!(!mine.is_empty(), "{method} has rows");
        let spp: Vec<u32> = mine.iter().map(|r| r[1].parse().expect("spp")).collect();
        assert!(
            spp.iter().copied().eq(1..=spp.len() as u32),
            "{method}: a row after every pass up to 16: {spp:?}"
        );
        let seconds: Vec<f64> = mine
            .iter()
            .map(|r| r[3].parse().expect("seconds"))
            .collect();
        assert!(
            seconds.windows(2).all(|w| w[1] > w[0]),
            "{method}: time grows"
        );
        for row in &mine {
            let flip: f64 = row[6].parse().expect("flip");
            assert!((0.0..=1.0).contains(&flip), "{method}: FLIP {flip}");
        }
    }
    // Path tracing converges toward raylab's own path-traced reference.
    let column = |name: &str, k: usize| -> Vec<f64> {
        rows.iter()
            .filter(|r| r[0] == name)
            .map(|r| r[k].parse().expect("a number"))
            .collect()
    };
    let path_error = column("path", 4);
    let (first, last) = (path_error[0], path_error[path_error.len() - 1]);
    assert!(
        path_error.len() >= 4 && last < 0.5 * first,
        "{path_error:?}"
    );
    let path_flip = column("path", 6);
    assert!(
        path_flip[path_flip.len() - 1] < path_flip[0],
        "FLIP falls as the image converges: {path_flip:?}"
    );
    let png = image::open(prefix.with_extension("png"))
        .expect("png written")
        .to_rgb8();
    // The first line's colour (Tableau blue) is drawn.
    let blue = png
        .pixels()
        .filter(|p| p.0[2] > 150 && p.0[0] < 80 && p.0[1] > 90 && p.0[1] < 150)
        .count();
    assert!(blue > 100, "the first curve is drawn ({blue} pixels)");
}

#[test]
fn stability_writes_every_case_for_both_methods_as_csv_and_a_chart() {
    let dir = tempfile::tempdir().expect("tempdir");
    let prefix = dir.path().join("stab");
    let stdout = raylab_ok(&[
        "stability",
        "--quick",
        "-o",
        prefix.to_str().expect("utf-8"),
    ]);
    assert!(
        stdout.contains("sphere far away"),
        "prints the table: {stdout}"
    );
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).expect("csv written");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some(
            "case,condition,value,method,trials,failures,failure_rate,refused,error_p99,ns_per_test"
        )
    );
    let rows: Vec<&str> = lines.collect();
    for case in renderer::diagnostics::stability::CASES {
        let mine: Vec<&&str> = rows.iter().filter(|r| r.starts_with(case.name)).collect();
        assert!(mine.len() >= 4, "{}: {} rows", case.name, mine.len());
    }
    // The sphere's lecture quadratic fails far away: its line rises off zero.
    let far_lecture = rows
        .iter()
        .find(|r| r.starts_with("sphere far away,") && r.contains(",1e4,lecture,"))
        .expect("the lecture sphere at 1e4 radii");
    let rate: f64 = far_lecture
        .split(',')
        .nth(6)
        .expect("rate")
        .parse()
        .expect("a number");
    assert!(rate > 0.05, "{far_lecture}");
    let png = image::open(prefix.with_extension("png"))
        .expect("png written")
        .to_rgb8();
    assert!(
        png.width() >= 1600 && png.height() >= 900,
        "{}×{}",
        png.width(),
        png.height()
    );
    // Both methods' lines are drawn (Tableau blue and red).
    let count = |f: &dyn Fn(&image::Rgb<u8>) -> bool| png.pixels().filter(|p| f(p)).count();
    let blue = count(&|p| p.0[2] > 150 && p.0[0] < 80 && p.0[1] > 90 && p.0[1] < 150);
    let red = count(&|p| p.0[0] > 180 && p.0[1] < 80 && p.0[2] < 80);
    assert!(blue > 500 && red > 500, "blue {blue} red {red} pixels");
}

#[test]
fn rendering_over_an_existing_file_replaces_it_and_says_so() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("seed.png");
    let small = ["--width", "16", "--height", "12", "--spp", "1"];
    let first = render(&asset("seed.xml"), &out, &small);
    assert!(!String::from_utf8_lossy(&first.stdout).contains("replaced"));
    std::fs::write(&out, "an earlier image").expect("write");
    let second = render(&asset("seed.xml"), &out, &small);
    let stdout = String::from_utf8_lossy(&second.stdout);
    assert!(
        stdout.contains("(replaced the existing file)"),
        "says so: {stdout}"
    );
    assert_eq!(
        read_png(&out).dimensions(),
        (16, 12),
        "the -o file is replaced"
    );
}

#[test]
fn stability_without_an_output_name_picks_a_free_one() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("stability.png"), "an earlier chart").expect("write");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(["stability", "--quick"])
        .current_dir(dir.path())
        .output()
        .expect("raylab runs");
    assert!(output.status.success());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("wrote stability-2.png"), "{stdout}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("stability.png")).expect("read"),
        "an earlier chart"
    );
    assert!(dir.path().join("stability-2.csv").is_file());
    assert!(
        !dir.path().join("stability.csv").exists(),
        "the pair stays together"
    );
}

/// 8-bit sRGB of linear `x`, from the sRGB formula in f64.
fn srgb8(x: f64) -> u8 {
    let v = if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (255.0 * v.clamp(0.0, 1.0)).round() as u8
}

/// A PNG's exposure scales its radiance by 2^EV before the curve: a grey
/// sky of 0.2 is written as the sRGB of 0.2, 0.4 (+1 EV) and 0.1 (−1 EV),
/// and through Khronos PBR Neutral as the sRGB of 0.4 − 0.04 (a grey below
/// its compression keeps all but the toe's offset). The scene's `<view>` is
/// the default the flags override, and the PNG records the view it was
/// shown with.
#[test]
fn exposure_doubles_the_radiance_of_a_png_before_its_tone_curve() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("grey.xml");
    let write = |view: &str| {
        std::fs::write(
            &scene,
            format!(
                "<scene>\n  <camera width=\"8\" height=\"6\"/>\n  <sky color=\"0.2 0.2 0.2\"/>\n{view}</scene>\n"
            ),
        )
        .expect("scene written");
    };
    let grey = |extra: &[&str]| -> u8 {
        let out = dir.path().join("grey.png");
        render(&scene, &out, &[&["--spp", "1"], extra].concat());
        let image = read_png(&out);
        let first = image.get_pixel(0, 0).0;
        assert!(image.pixels().all(|p| p.0 == first), "a uniform grey");
        assert!(first[0] == first[1] && first[1] == first[2]);
        first[0]
    };
    write("");
    assert_eq!(grey(&[]), srgb8(0.2));
    assert_eq!(grey(&["--exposure", "1"]), srgb8(0.4));
    assert_eq!(grey(&["--exposure", "-1"]), srgb8(0.1));
    assert_eq!(
        grey(&["--exposure", "1", "--tonemap", "neutral"]),
        srgb8(0.36)
    );
    write("  <view exposure=\"1\"/>\n");
    assert_eq!(grey(&[]), srgb8(0.4), "the scene's view");
    assert_eq!(grey(&["--exposure", "0"]), srgb8(0.2), "the flag wins");
    let out = dir.path().join("grey.png");
    render(&scene, &out, &["--spp", "1"]);
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&out).expect("the PNG exists"),
    ));
    let reader = decoder.read_info().expect("a PNG");
    let view = reader
        .info()
        .utf8_text
        .iter()
        .find(|c| c.keyword == "raylab:view")
        .map(|c| c.get_text().expect("utf-8"));
    assert_eq!(view.as_deref(), Some("exposure=+1 EV tonemap=clamp"));

    let refused = raylab(&[
        "render",
        scene.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
        "--exposure",
        "30",
    ]);
    assert!(!refused.status.success());
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(
        message.contains("--exposure 30") && message.contains("-20 to 20"),
        "{message}"
    );
}

/// The RGB channels of an EXR, pixel by pixel (row 0 at the top).
fn exr_rgb(path: &std::path::Path) -> Vec<[f32; 3]> {
    use exr::prelude::*;
    let image = read_all_flat_layers_from_file(path).expect("an EXR");
    let layer = &image.layer_data[0];
    let channel = |name: &str| -> Vec<f32> {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .expect("the channel")
            .sample_data
            .values_as_f32()
            .collect()
    };
    let (r, g, b) = (channel("R"), channel("G"), channel("B"));
    (0..r.len()).map(|k| [r[k], g[k], b[k]]).collect()
}

/// `raylab render seed.xml` at 40×30 with `extra` to `dir/name`.
fn seed_part(dir: &std::path::Path, name: &str, extra: &[&str]) -> std::path::PathBuf {
    let out = dir.join(name);
    let mut args = vec!["--width", "40", "--height", "30", "--integrator", "path"];
    args.extend_from_slice(extra);
    render(&asset("seed.xml"), &out, &args);
    out
}

#[test]
fn a_render_split_into_rectangles_and_merged_is_the_whole_render_bit_for_bit() {
    let dir = tempfile::tempdir().expect("tempdir");
    let whole = seed_part(dir.path(), "whole.exr", &["--spp", "3"]);
    let parts: Vec<_> = [
        ("0", "0", "40", "11"),
        ("0", "11", "17", "30"),
        ("17", "11", "40", "30"),
    ]
    .iter()
    .enumerate()
    .map(|(k, &(x0, y0, x1, y1))| {
        seed_part(
            dir.path(),
            &format!("part{k}.exr"),
            &["--spp", "3", "--crop", x0, y0, x1, y1],
        )
    })
    .collect();
    let merged = dir.path().join("merged.exr");
    let mut args = vec!["merge", merged.to_str().expect("utf-8")];
    args.extend(parts.iter().map(|p| p.to_str().expect("utf-8")));
    raylab_ok(&args);
    let (want, got) = (exr_rgb(&whole), exr_rgb(&merged));
    assert_eq!(got.len(), want.len());
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert_eq!(g.map(f32::to_bits), w.map(f32::to_bits), "pixel {k}");
    }
    // A part alone: its rectangle rendered, the rest black.
    let part = exr_rgb(&parts[0]);
    assert_eq!(part[5 * 40 + 7], want[5 * 40 + 7]);
    assert_eq!(part[20 * 40 + 7], [0.0; 3]);
}

/// The README's farm script: GNU parallel renders 4 bands of rows on 2
/// processes and `raylab merge` joins them into the whole render, bit for bit.
#[test]
fn the_gnu_parallel_farm_script_renders_bands_on_two_processes_into_the_whole_render() {
    let found = std::process::Command::new("sh")
        .args(["-c", "command -v parallel"])
        .output()
        .expect("sh");
    assert!(
        found.status.success(),
        "GNU parallel is not installed: scripts/setup.sh installs it"
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let whole = seed_part(dir.path(), "whole.exr", &["--spp", "3"]);
    let merged = dir.path().join("farmed.exr");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let output = std::process::Command::new("bash")
        .arg(root.join("../scripts/farm/parallel.sh"))
        .arg(asset("seed.xml"))
        .args(["40", "30"])
        .arg(&merged)
        .args([
            "--bands",
            "4",
            "--jobs",
            "2",
            "--",
            "--integrator",
            "path",
            "--spp",
            "3",
        ])
        .env("RAYLAB", env!("CARGO_BIN_EXE_raylab"))
        .output()
        .expect("bash");
    assert!(
        output.status.success(),
        "the farm script failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let (want, got) = (exr_rgb(&whole), exr_rgb(&merged));
    assert_eq!(got.len(), want.len());
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert_eq!(g.map(f32::to_bits), w.map(f32::to_bits), "pixel {k}");
    }
}

#[test]
fn a_render_split_into_sample_ranges_and_merged_is_the_whole_render_within_rounding() {
    let dir = tempfile::tempdir().expect("tempdir");
    let whole = seed_part(dir.path(), "whole.exr", &["--spp", "5"]);
    let early = seed_part(dir.path(), "early.exr", &["--samples", "0..2"]);
    let late = seed_part(dir.path(), "late.exr", &["--samples", "2..5"]);
    let merged = dir.path().join("merged.exr");
    raylab_ok(&[
        "merge",
        merged.to_str().expect("utf-8"),
        late.to_str().expect("utf-8"),
        early.to_str().expect("utf-8"),
    ]);
    let (want, got) = (exr_rgb(&whole), exr_rgb(&merged));
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        for c in 0..3 {
            let scale = w[c].abs().max(1e-3);
            assert!(
                (g[c] - w[c]).abs() <= 1e-6 * scale,
                "pixel {k} channel {c}: {} against {}",
                g[c],
                w[c]
            );
        }
    }
}

#[test]
fn merging_overlapping_missing_or_mismatched_parts_is_an_error_that_names_them() {
    let dir = tempfile::tempdir().expect("tempdir");
    let top = seed_part(
        dir.path(),
        "top.exr",
        &["--spp", "1", "--crop", "0", "0", "40", "16"],
    );
    let low = seed_part(
        dir.path(),
        "low.exr",
        &["--spp", "1", "--crop", "0", "10", "40", "30"],
    );
    let other = dir.path().join("other.exr");
    render(
        &asset("seed.xml"),
        &other,
        &[
            "--width", "40", "--height", "31", "--spp", "1", "--crop", "0", "16", "40", "31",
        ],
    );
    let merged = dir.path().join("merged.exr");
    let fails = |parts: &[&std::path::Path], says: &[&str]| {
        let mut args = vec!["merge", merged.to_str().expect("utf-8")];
        args.extend(parts.iter().map(|p| p.to_str().expect("utf-8")));
        let output = raylab(&args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        for word in says {
            assert!(stderr.contains(word), "{word:?} in {stderr}");
        }
        assert!(!merged.exists(), "nothing written");
    };
    fails(&[&top, &low], &["top.exr", "low.exr", "overlap"]);
    fails(&[&top], &["leave pixels", "(0, 16)"]);
    fails(&[&top, &other], &["other.exr", "different image size"]);
    fails(&[&top, &top], &["sample ranges", "overlap"]);
    // Asked for badly: an empty or outside rectangle, a split of an adaptive render.
    for bad in [
        &["--crop", "5", "5", "5", "9"][..],
        &["--crop", "0", "0", "41", "30"],
        &["--samples", "3..3"],
        &["--samples", "0..2", "--adaptive"],
    ] {
        let mut args = vec!["render", "x.xml"];
        let scene = asset("seed.xml");
        args[1] = scene.to_str().expect("utf-8");
        let out = dir.path().join("bad.exr");
        args.extend_from_slice(&["-o", out.to_str().expect("utf-8")]);
        args.extend_from_slice(&["--width", "40", "--height", "30"]);
        args.extend_from_slice(bad);
        let output = raylab(&args);
        assert_eq!(output.status.code(), Some(2), "{bad:?}");
        assert!(!out.exists(), "{bad:?}: nothing written");
    }
}

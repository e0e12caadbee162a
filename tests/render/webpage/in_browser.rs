//! The page in a real browser (headless Chromium driven by `browser.js`): no console error, no
//! network request, the same picture as `cutaway render`, checkboxes, variants and the removed
//! piece's slider.

use super::*;

/// The browser the tests drive, or why they skip.
fn browser() -> Option<(PathBuf, PathBuf)> {
    let Some(package) = std::env::var_os("CUTAWAY_PLAYWRIGHT").map(PathBuf::from) else {
        println!(
            "skipped: CUTAWAY_PLAYWRIGHT is not set (npm install playwright-core and apt-get \
             install chromium, then set it to the package folder, as .ci/run does)"
        );
        return None;
    };
    assert!(
        package.join("package.json").is_file(),
        "CUTAWAY_PLAYWRIGHT={} is not the playwright-core package folder",
        package.display()
    );
    let chromium = std::env::var_os("CUTAWAY_CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    assert!(chromium.is_file(), "no Chromium at {}", chromium.display());
    Some((package, chromium))
}

/// What `webpage/browser.js` reports.
struct Report {
    json: serde_json::Value,
}

impl Report {
    fn shot(&self, name: &str) -> RgbaImage {
        let step = self.json["steps"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| {
                s["shot"]
                    .as_str()
                    .is_some_and(|p| p.ends_with(&format!("/{name}.png")))
            })
            .unwrap_or_else(|| panic!("no shot {name}"));
        image::open(step["shot"].as_str().unwrap())
            .unwrap()
            .to_rgba8()
    }

    /// The page's controls as pixel rectangles `[x, y, w, h]` (left out of comparisons).
    fn overlays(&self) -> Vec<[f64; 4]> {
        self.json["overlays"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| {
                let v: Vec<f64> = r
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect();
                [v[0], v[1], v[2], v[3]]
            })
            .collect()
    }
}

/// Opens `page` in the browser, takes `steps`, and checks that the page logged no error or
/// warning and requested nothing from the network.
fn drive(
    browser: &(PathBuf, PathBuf),
    page: &Path,
    shots: &Path,
    steps: serde_json::Value,
) -> Report {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/render/webpage/browser.js");
    let plan = serde_json::json!({ "steps": steps });
    let output = Command::new("node")
        .arg(script)
        .arg(page)
        .arg(shots)
        .arg(plan.to_string())
        .env("CUTAWAY_PLAYWRIGHT", &browser.0)
        .env("CUTAWAY_CHROMIUM", &browser.1)
        .output()
        .expect("node runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "browser.js: {stderr}");
    let json: serde_json::Value = serde_json::from_slice(&output.stdout)
        .unwrap_or_else(|e| panic!("browser.js printed no report ({e}): {stderr}"));
    assert_eq!(
        json["errors"],
        serde_json::json!([]),
        "the page logged errors"
    );
    assert_eq!(
        json["requests"],
        serde_json::json!([]),
        "the page reached out"
    );
    println!("page ready in {} ms", json["loadMs"]);
    Report { json }
}

/// How far a page screenshot is from `cutaway render` of the same session.
#[derive(Debug)]
struct Agreement {
    /// Per structure seen (by ray casting) on enough interior pixels: name, pixels compared,
    /// mean colour distance (RGB, 0..255 per channel, Euclidean) and the share of its pixels
    /// whose colours agree within [`PIXEL_TOLERANCE`].
    structures: Vec<(String, usize, f64, f64)>,
    /// The same for the background.
    background: (usize, f64, f64),
}

/// A pixel agrees when no channel differs by more than this (of 255).
const PIXEL_TOLERANCE: i32 = 24;
/// A structure is compared where ray casting sees it on at least this many interior samples.
const MIN_SAMPLES: usize = 150;

/// Compares `page` with `render` where `scene` (as its session's active variant is cut) shows
/// each structure: samples every other pixel whose whole 5×5 neighbourhood sees the same
/// structure and the same kind of face (so edges, which the two anti-alias differently, and the
/// contour lines along the cut are left out), outside the page's controls.
fn agreement(
    scene: &cutaway::scene::Scene,
    page: &RgbaImage,
    render: &RgbaImage,
    overlays: &[[f64; 4]],
) -> Agreement {
    let (width, height) = page.dimensions();
    assert_eq!(render.dimensions(), (width, height));
    let preview = preview_geometry(scene);
    let step = 2;
    let grid =
        cutaway::annotate::visible::visible_grid(scene, Some(&preview), [width, height], step);
    let covered = |x: u32, y: u32| {
        overlays.iter().any(|r| {
            let (x, y) = (x as f64, y as f64);
            x >= r[0] - 3.0 && x <= r[0] + r[2] + 3.0 && y >= r[1] - 3.0 && y <= r[1] + r[3] + 3.0
        })
    };
    let key = |c: u32, r: u32| {
        let i = (r * grid.columns + c) as usize;
        (grid.cells[i], grid.cut_face[i])
    };
    let mut sums: std::collections::BTreeMap<Option<u32>, (usize, f64, usize)> = Default::default();
    for r in 2..grid.rows.saturating_sub(2) {
        for c in 2..grid.columns.saturating_sub(2) {
            let k = key(c, r);
            if (r - 2..=r + 2).any(|rr| (c - 2..=c + 2).any(|cc| key(cc, rr) != k)) {
                continue;
            }
            let [x, y] = grid.pixel(c, r).map(|v| v as u32);
            if covered(x, y) {
                continue;
            }
            let a = page.get_pixel(x, y).0.map(i32::from);
            let b = render.get_pixel(x, y).0.map(i32::from);
            let distance = ((0..3)
                .map(|k| ((a[k] - b[k]) * (a[k] - b[k])) as f64)
                .sum::<f64>())
            .sqrt();
            let agrees = (0..3).all(|k| (a[k] - b[k]).abs() <= PIXEL_TOLERANCE);
            let entry = sums.entry(k.0).or_default();
            entry.0 += 1;
            entry.1 += distance;
            entry.2 += agrees as usize;
        }
    }
    let summary =
        |(n, d, a): (usize, f64, usize)| (n, d / n.max(1) as f64, a as f64 / n.max(1) as f64);
    let background = summary(sums.get(&None).copied().unwrap_or_default());
    let structures = sums
        .iter()
        .filter_map(|(m, v)| Some((m.as_ref()?, *v)))
        .filter(|(_, v)| v.0 >= MIN_SAMPLES)
        .map(|(&m, v)| {
            let (n, d, a) = summary(v);
            (scene.models[m as usize].model.name.clone(), n, d, a)
        })
        .collect();
    Agreement {
        structures,
        background,
    }
}

/// The tolerance of the comparison (see the module doc and [`agreement`]): every structure the
/// render shows on at least [`MIN_SAMPLES`] interior samples has a mean colour distance under
/// `max_mean` and agrees within [`PIXEL_TOLERANCE`] on at least `min_share` of them.
fn same_picture(what: &str, agreement: &Agreement, max_mean: f64, min_share: f64) {
    println!("{what}: background {:?}", agreement.background);
    for (name, n, mean, share) in &agreement.structures {
        println!(
            "{what}: {name}: {n} samples, mean distance {mean:.1}, {:.1} % agree",
            share * 100.0
        );
    }
    assert!(
        !agreement.structures.is_empty(),
        "{what}: no structure compared"
    );
    assert!(
        agreement.background.1 < 3.0,
        "{what}: background {:?}",
        agreement.background
    );
    for (name, n, mean, share) in &agreement.structures {
        assert!(
            *mean <= max_mean && *share >= min_share,
            "{what}: {name} ({n} samples): mean distance {mean:.1} (at most {max_mean}), {:.1} % agree (at least {:.0} %)",
            share * 100.0,
            min_share * 100.0
        );
    }
}

/// The default head with a cut, in the browser: the first picture is `cutaway render`'s (the
/// session's camera, colours, walls, the removed piece at 30 %); a structure's checkbox hides
/// it; the variant choice shows the crown cut as `cutaway render` draws that variant; the
/// removed piece's slider at 0 hides the removed skin.
#[test]
fn the_head_page_in_a_browser_shows_what_render_shows() {
    let Some(browser) = browser() else { return };
    let (_, variants) = head_sessions();
    let out = out_dir();
    let page = out.join("head-variants.html");
    export(variants, &page, &["--title", "Head atlas: two cuts"]);
    let scene = cutaway::session::load(variants).unwrap();
    // The structure to hide: the deep structure seen most in the cut (by ray casting).
    let preview = preview_geometry(&scene);
    let grid = cutaway::annotate::visible::visible_grid(&scene, Some(&preview), [1280, 800], 4);
    let mut seen = vec![0usize; scene.models.len()];
    for m in grid.cells.iter().flatten() {
        seen[*m as usize] += 1;
    }
    let hidden = (1..scene.models.len()).max_by_key(|&m| seen[m]).unwrap();
    println!(
        "hiding {} ({} cells)",
        scene.models[hidden].model.name, seen[hidden]
    );
    let report = drive(
        &browser,
        &page,
        &out,
        serde_json::json!([
            {"shot": "head-page"},
            {"hide": hidden},
            {"shot": "head-page-hidden"},
            {"show": hidden},
            {"removed": 0},
            {"shot": "head-page-no-removed"},
            {"variant": 1},
            {"shot": "head-page-variant-1"},
        ]),
    );
    let overlays = report.overlays();
    let render_0 = render(variants, &out.join("head-render.png"));
    let first = agreement(&scene, &report.shot("head-page"), &render_0, &overlays);
    same_picture("head", &first, 20.0, 0.85);

    // Hidden: where the structure was seen, the page now shows something else.
    let before = report.shot("head-page");
    let after = report.shot("head-page-hidden");
    let (mut cells, mut changed) = (0, 0);
    for r in 0..grid.rows {
        for c in 0..grid.columns {
            if grid.at(c, r) != Some(hidden as u32) {
                continue;
            }
            let [x, y] = grid.pixel(c, r).map(|v| v as u32);
            cells += 1;
            let (a, b) = (before.get_pixel(x, y).0, after.get_pixel(x, y).0);
            changed += (0..3).any(|k| (a[k] as i32 - b[k] as i32).abs() > 24) as usize;
        }
    }
    assert!(
        changed as f64 >= 0.8 * cells as f64,
        "hiding {} changed {changed} of its {cells} cells",
        scene.models[hidden].model.name
    );
    let step = |k: usize| &report.json["steps"][k]["state"];
    assert_eq!(step(1)["visible"][hidden], false);
    assert_eq!(step(3)["visible"][hidden], true);
    assert_eq!(step(4)["removedOpacity"], 0.0);

    // The other variant, as `cutaway render` draws it with that variant active.
    let mut file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(variants).unwrap()).unwrap();
    file["active_variant"] = 1.into();
    file["cutters"] = file["variants"][1]["cutters"].clone();
    let crown = out.join("head-variant-1.json");
    std::fs::write(&crown, file.to_string()).unwrap();
    let render_1 = render(&crown, &out.join("head-render-variant-1.png"));
    let crown_scene = cutaway::session::load(&crown).unwrap();
    assert_eq!(report.json["state"]["variant"], 1);
    let second = agreement(
        &crown_scene,
        &report.shot("head-page-variant-1"),
        &render_1,
        &overlays,
    );
    same_picture("head, crown", &second, 20.0, 0.85);
    // And the first variant's picture is not that one: the switch changed the picture.
    let differ = agreement(
        &crown_scene,
        &report.shot("head-page"),
        &render_1,
        &overlays,
    );
    assert!(
        differ
            .structures
            .iter()
            .any(|(_, _, _, share)| *share < 0.8),
        "the variant switch changed nothing: {differ:?}"
    );
}

/// The chest CT's segmentation cut from the front with the CT on the walls (bone window), in
/// the browser: the walls show the image as `cutaway render` draws it.
#[test]
fn the_chest_page_shows_the_ct_on_the_walls() {
    let Some(browser) = browser() else { return };
    let Some(chest) = chest_dir() else { return };
    let out = out_dir();
    let plane = |x: f64| {
        serde_json::json!([
            [x, 200, -90],
            [x, -100, -90],
            [x, -100, -290],
            [x, 200, -290]
        ])
    };
    let planes = serde_json::json!([plane(150.0), plane(0.0), plane(-150.0)]);
    let cutters: Vec<serde_json::Value> = [0, 2, 3, 4, 5, 6]
        .iter()
        .map(|t| serde_json::json!({"target": t, "kind": "straight", "planes": planes}))
        .collect();
    let session = serde_json::json!({
        "format": "cutaway-session/2",
        "models": [{"path": chest.join("Segmentation.seg.nrrd")}],
        "cutters": cutters,
        "camera": {"eye": [160, 720, -20], "target": [0, 0, -190], "up": [0, 0, 1], "fov_y_deg": 30},
        "image": {"path": chest.join("CTChest4.nrrd"), "window": [400, 1800]}
    });
    let path = out.join("chest.json");
    std::fs::write(&path, serde_json::to_string_pretty(&session).unwrap()).unwrap();
    let page = out.join("chest.html");
    let summary = export(
        &path,
        &page,
        &["--title", "Chest CT: the scan on the cut walls"],
    );
    println!("chest: {summary}");
    let report = drive(
        &browser,
        &page,
        &out,
        serde_json::json!([{"shot": "chest-page"}]),
    );
    let rendered = render(&path, &out.join("chest-render.png"));
    let scene = cutaway::session::load(&path).unwrap();
    let result = agreement(
        &scene,
        &report.shot("chest-page"),
        &rendered,
        &report.overlays(),
    );
    same_picture("chest", &result, 20.0, 0.85);
}

/// The chest CT folder of the real data (`$CUTAWAY_ANATOMY/volumes/slicerio_chest`).
fn chest_dir() -> Option<PathBuf> {
    let Some(root) = std::env::var_os("CUTAWAY_ANATOMY").map(PathBuf::from) else {
        println!("skipped: CUTAWAY_ANATOMY is not set");
        return None;
    };
    let dir = root.join("volumes/slicerio_chest");
    if dir.join("CTChest4.nrrd").is_file() && dir.join("Segmentation.seg.nrrd").is_file() {
        Some(dir)
    } else {
        println!("skipped: no chest CT in {}", dir.display());
        None
    }
}

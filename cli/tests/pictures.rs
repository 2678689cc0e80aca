//! The drawings people look at: every `docs/*.svg` and a fresh `cuesight shot --svg`,
//! rendered to PNG with resvg under `target/pictures/` (open them to look), and checked
//! for what makes a picture unreadable: a label that leaves the canvas, labels that
//! overlap, a picture that renders (nearly) blank, text that renders without a font.
//!
//! `cargo test -p cuesight-cli --test pictures` (part of `cargo xtask test`'s host
//! tests). Fonts: the system's, `sans-serif` mapped to DejaVu Sans when installed.

use std::path::{Path, PathBuf};
use std::process::Command;

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{self, Node, Rect, Tree};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn options() -> usvg::Options<'static> {
    let mut options = usvg::Options::default();
    options.fontdb_mut().load_system_fonts();
    if options
        .fontdb
        .faces()
        .any(|f| f.families.iter().any(|(name, _)| name == "DejaVu Sans"))
    {
        options.fontdb_mut().set_sans_serif_family("DejaVu Sans");
    }
    options
}

/// Every text element's box (absolute, px), with its group ids from the root down.
fn texts(group: &usvg::Group, ids: &mut Vec<String>, out: &mut Vec<(Vec<String>, Rect)>) {
    for node in group.children() {
        match node {
            Node::Group(g) => {
                ids.push(g.id().to_owned());
                texts(g, ids, out);
                ids.pop();
            }
            Node::Text(t) => out.push((ids.clone(), t.abs_bounding_box())),
            _ => {}
        }
    }
}

/// Renders `svg` to `target/pictures/<name>.png` and checks it; returns the text boxes.
fn render_and_check(name: &str, svg: &[u8]) -> Vec<(Vec<String>, Rect)> {
    let options = options();
    let tree = Tree::from_data(svg, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height()).expect("a canvas");
    resvg::render(&tree, Transform::default(), &mut pixmap.as_mut());
    let out = root().join("target").join("pictures");
    std::fs::create_dir_all(&out).expect("target/pictures");
    pixmap
        .save_png(out.join(format!("{name}.png")))
        .expect("PNG written");

    // Not blank: at least 5 % of the pixels differ from the first one.
    let pixels = pixmap.pixels();
    let background = pixels[0];
    let drawn = pixels.iter().filter(|p| **p != background).count();
    assert!(
        drawn * 20 > pixels.len(),
        "{name}: only {drawn} of {} pixels drawn",
        pixels.len()
    );

    let mut boxes = Vec::new();
    texts(tree.root(), &mut Vec::new(), &mut boxes);
    let (w, h) = (size.width() as f32, size.height() as f32);
    for (ids, b) in &boxes {
        // A text without a font has no outline: an empty box.
        assert!(
            b.width() > 0.0,
            "{name}: a text in {ids:?} rendered empty (no font?)"
        );
        assert!(
            b.left() >= -0.5 && b.top() >= -0.5 && b.right() <= w + 0.5 && b.bottom() <= h + 0.5,
            "{name}: a label in {ids:?} leaves the {w} x {h} canvas: {b:?}"
        );
    }
    boxes
}

#[test]
fn docs_drawings_render_with_every_label_on_the_canvas() {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(root().join("docs")).expect("docs/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "svg") {
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            let svg = std::fs::read(&path).expect("readable");
            let boxes = render_and_check(&name, &svg);
            assert!(!boxes.is_empty(), "{name}: no text at all");
            let all: Vec<Rect> = boxes.iter().map(|(_, b)| *b).collect();
            no_overlap(&name, &all);
            names.push(name);
        }
    }
    names.sort();
    assert!(
        names.len() >= 4,
        "expected the drawings of docs/ (shot, tradeoff, low speed, domain map): {names:?}"
    );
}

/// A fresh drawing of the documented scene: the key's labels (and the tip inset's)
/// overlap nothing else in the key, and the key, scale bar and tip inset are there.
#[test]
fn shot_drawing_key_labels_do_not_overlap() {
    let path = std::env::temp_dir().join(format!("cuesight-pictures-{}.svg", std::process::id()));
    let status = Command::new(env!("CARGO_BIN_EXE_cuesight"))
        .args(["shot", "--scene"])
        .arg(root().join("cli/scenes/cut_to_corner.toml"))
        .arg("--svg")
        .arg(&path)
        .output()
        .expect("cuesight runs");
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let svg = std::fs::read(&path).expect("svg written");
    std::fs::remove_file(&path).ok();
    let text = String::from_utf8_lossy(&svg);
    for id in ["legend", "scale-bar", "tip-offset", "diamonds"] {
        assert!(text.contains(&format!("id=\"{id}\"")), "no #{id}");
    }
    let boxes = render_and_check("shot-cut-to-corner", &svg);
    let key: Vec<Rect> = boxes
        .iter()
        .filter(|(ids, _)| ids.iter().any(|id| id == "legend"))
        .map(|(_, b)| *b)
        .collect();
    assert!(key.len() >= 9, "{} labels in the key", key.len());
    no_overlap("shot key", &key);
}

/// No two labels overlap (boxes touching within half a pixel are fine).
fn no_overlap(name: &str, boxes: &[Rect]) {
    let mut clashes = Vec::new();
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            let overlap = a.left() + 0.5 < b.right()
                && b.left() + 0.5 < a.right()
                && a.top() + 0.5 < b.bottom()
                && b.top() + 0.5 < a.bottom();
            if overlap {
                clashes.push(format!("{a:?} and {b:?}"));
            }
        }
    }
    assert!(
        clashes.is_empty(),
        "{name}: labels overlap:\n{}",
        clashes.join("\n")
    );
}

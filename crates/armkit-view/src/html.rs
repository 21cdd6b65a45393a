//! The viewer as HTML: a block (canvas, controls, the scene as JSON) to put
//! in a page, and a whole page. The scripts are classic scripts (pages open
//! from `file://`), inlined or loaded from one shared file beside the page.

use crate::scene::Scene;

/// three.js's core and OrbitControls as the global `THREE` (built by
/// `scripts/build-viewer-asset.sh`; MIT, `assets/three.LICENSE`).
pub const THREE_BUNDLE: &str = include_str!("../assets/three.bundle.js");
/// armkit's viewer script (`assets/viewer.js`).
pub const VIEWER_SCRIPT: &str = include_str!("../assets/viewer.js");
/// three.js's licence text, shipped beside a shared asset file.
pub const THREE_LICENSE: &str = include_str!("../assets/three.LICENSE");
/// The file name of the shared asset ([`asset_script`]).
pub const ASSET_FILE: &str = "armkit-viewer.js";

/// The shared asset file's content: the three.js bundle, then the viewer.
pub fn asset_script() -> String {
    format!("{THREE_BUNDLE}\n{VIEWER_SCRIPT}")
}

/// How a page gets the scripts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Scripts {
    /// Inlined in the page (one portable file, ~600 kB more).
    Inline,
    /// A `<script src>` to the shared asset file at this relative URL
    /// (e.g. `../armkit-viewer.js`), written once beside the pages.
    Shared(String),
}

impl Scripts {
    /// The `<script>` elements, placed after the viewer blocks.
    pub fn to_html(&self) -> String {
        match self {
            // A literal `</script>` cannot occur inside: the minified bundle
            // writes none (checked by a test).
            Scripts::Inline => format!("<script>\n{}\n</script>\n", asset_script()),
            Scripts::Shared(url) => format!("<script src=\"{}\"></script>\n", escape(url)),
        }
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// CSS of the viewer block.
pub const STYLE: &str = ".armkit-view{border:1px solid #ddd;padding:6px;margin:8px 0;max-width:820px}
.armkit-canvas{width:800px;height:480px;max-width:100%}.armkit-controls{font:0.9em sans-serif;margin-top:4px}
.armkit-controls button{min-width:4em}.armkit-joints{font:0.85em monospace;color:#333;margin-top:4px}
.armkit-status{color:#a33}.armkit-fallback{display:none}.armkit-legend{color:#666;font-size:0.85em}";

/// The viewer block for `scene`; `id` is unique in the page; `fallback` is
/// shown instead when the browser has no WebGL (e.g. a 2-D figure).
pub fn viewer_block(scene: &Scene, id: &str, fallback: Option<&str>) -> String {
    // `</` cannot end the JSON's script element early.
    let json = scene.to_json().to_string().replace("</", "<\\/");
    let beam = scene.beam.as_ref().map_or(String::new(), |b| {
        format!(
            " <label><input type=\"checkbox\" class=\"armkit-beam\" checked> beam deflection magnified {}x</label>",
            crate::scene::format_factor(b.magnification)
        )
    });
    let legend = if scene.path_flags.iter().any(|&f| f) {
        "End-effector path: magenta; red where the motion is inside the singular region."
    } else if scene.path.is_empty() {
        ""
    } else {
        "End-effector path: magenta."
    };
    format!(
        r#"<div class="armkit-view" id="{id}" data-scene="{id}-scene">
<div class="armkit-canvas"></div>
<div class="armkit-controls"><button type="button" class="armkit-play">play</button>
<input type="range" class="armkit-slider" min="0" max="0" value="0" style="width:360px" aria-label="time">
<span class="armkit-time"></span>
<label>speed <select class="armkit-speed"><option value="0.25">0.25x</option><option value="0.5">0.5x</option><option value="1" selected>1x</option><option value="2">2x</option><option value="4">4x</option></select></label>
<label><input type="checkbox" class="armkit-frames"> joint frames</label>{beam}</div>
<div class="armkit-joints"></div>
<div class="armkit-legend">Drag to orbit, right-drag to pan, wheel to zoom. Floor grid: <span class="armkit-cell">0.1 m</span> squares; axes x red, y green, z blue. {legend}</div>
<div class="armkit-status"></div>
<div class="armkit-fallback">{fallback}</div>
<script type="application/json" id="{id}-scene">{json}</script>
</div>
"#,
        fallback = fallback.unwrap_or("")
    )
}

/// A whole page showing `scene`, scripts inlined: one portable file.
pub fn standalone_page(scene: &Scene) -> String {
    let warnings: String = scene
        .warnings
        .iter()
        .map(|w| format!("<p class=\"armkit-status\">warning: {}</p>\n", escape(w)))
        .collect();
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{title}</title>\n<style>body{{font-family:sans-serif;margin:16px}}{STYLE}</style></head>\n<body>\n<h1>{title}</h1>\n{warnings}{block}{scripts}</body></html>\n",
        title = escape(&scene.title),
        block = viewer_block(scene, "armkit-view-0", None),
        scripts = Scripts::Inline.to_html(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bundle_is_a_classic_script_that_cannot_close_its_element() {
        assert!(!THREE_BUNDLE.contains("</script"));
        assert!(!VIEWER_SCRIPT.contains("</script"));
        // No ES-module syntax at the top level (file:// refuses modules).
        assert!(!THREE_BUNDLE.contains("\nexport ") && !THREE_BUNDLE.contains("\nimport "));
        assert!(THREE_BUNDLE.contains("OrbitControls") && THREE_LICENSE.contains("MIT"));
    }

    #[test]
    fn the_page_has_no_network_reference_and_escapes_the_scene() {
        let scene = Scene {
            title: "a </script> robot".into(),
            times: vec![0.0],
            configurations: vec![vec![]],
            poses: vec![vec![]],
            ..Scene::default()
        };
        let page = standalone_page(&scene);
        assert!(!page.contains("src=\"http") && !page.contains("href=\"http"));
        assert_eq!(
            page.matches("</script>").count(),
            2,
            "JSON and the inline scripts"
        );
    }
}

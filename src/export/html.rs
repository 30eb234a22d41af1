//! The viewer page: one HTML file with everything inline, so it opens from disk (`file://`)
//! with no network: three.js with its `GLTFLoader` and `OrbitControls` (npm `three`, pinned in
//! `tools/js/package.json`, bundled into `assets/three-bundle.min.js`, MIT licence in
//! `assets/three.LICENSE`), the viewer's own script (`assets/viewer.js`) and the `.glb` as
//! base64.
//!
//! The page exposes `window.viaroad` for tests: `ready`, `error`, `setTime(f)` (f in 0–1 of
//! the animation, pauses it), `only(names)` (draw only the named nodes and what hangs under
//! them; `null` draws all) and `pixels()` (the canvas as base64 RGBA, bottom row first).

use super::Legend;

/// three.js r187 and the two add-ons, as one classic script (`npm run bundle-three`).
const THREE_BUNDLE: &str = include_str!("../../assets/three-bundle.min.js");
/// three.js's MIT licence, carried into every page that embeds it.
const THREE_LICENSE: &str = include_str!("../../assets/three.LICENSE");
/// The page's script.
const VIEWER: &str = include_str!("../../assets/viewer.js");

/// Standard base64 (RFC 4648, with padding).
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= c.len() {
                out.push(A[(n >> shift & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Text made safe inside an HTML element.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A script's text made safe inside `<script>`: a `</script` in a string would end the element.
fn script(s: &str) -> String {
    s.replace("</script", "<\\/script")
}

/// A length as the legend shows it: three decimals, exponent notation from 10⁶ on (bounds
/// reach 10¹⁰⁰), never `-0.000`.
fn length(x: f64) -> String {
    let x = x + 0.0;
    if x.abs() >= 1e6 {
        format!("{x:.3e}")
    } else {
        format!("{x:.3}")
    }
}

/// The legend's rows below the title, as HTML: what the plan is, each path trace in its colour
/// (a colliding one as a warning), the robot. Written into the page, not left to the script,
/// so that a collision is said even where the model does not load.
fn legend_rows(l: &Legend) -> String {
    let mut rows = Vec::new();
    let about: Vec<&str> = [l.space.as_str(), l.source.as_str()]
        .into_iter()
        .filter(|s| !s.is_empty())
        .collect();
    if !about.is_empty() {
        rows.push(format!("<div>{}</div>", escape(&about.join(" · "))));
    }
    for p in &l.paths {
        let class = if p.collides {
            r#" class="warning""#
        } else {
            ""
        };
        rows.push(format!(
            r#"<div{class}><span class="swatch" style="background:{}"></span>{}, length {}</div>"#,
            escape(&p.colour),
            escape(&p.label),
            length(p.length)
        ));
    }
    let calls = l
        .calls
        .map_or(String::new(), |c| format!(" · oracle calls {c}"));
    if l.bodies.is_empty() {
        rows.push(format!(
            r#"<div><span class="swatch" style="background:{}"></span>robot{calls}</div>"#,
            super::colour::css(super::colour::ROBOT)
        ));
    } else {
        let bodies: Vec<String> = l
            .bodies
            .iter()
            .map(|b| {
                format!(
                    r#"<span class="swatch" style="background:{}"></span>{}"#,
                    escape(&b.colour),
                    escape(&b.name)
                )
            })
            .collect();
        rows.push(format!("<div>{}{calls}</div>", bodies.join(" ")));
    }
    rows.join("\n")
}

/// The page showing `glb` (see the module doc), titled by the legend's scene, with the legend.
pub fn page(legend: &Legend, glb: &[u8]) -> String {
    let title = &legend.scene;
    let licence = THREE_LICENSE.replace("*/", "* /");
    format!(
        r#"<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>viaroad: {title}</title>
<style>
html, body {{ margin: 0; height: 100%; overflow: hidden; font: 14px system-ui, sans-serif; background: #f5f7fa; }}
#view {{ position: absolute; inset: 0; }}
#legend {{ position: absolute; top: 8px; left: 8px; background: rgba(255,255,255,0.9); padding: 6px 10px; border-radius: 4px; line-height: 1.5; }}
#legend .swatch {{ display: inline-block; width: 18px; height: 4px; vertical-align: middle; margin-right: 4px; }}
#controls {{ position: absolute; bottom: 8px; left: 8px; right: 8px; display: flex; gap: 8px; align-items: center; background: rgba(255,255,255,0.9); padding: 6px 10px; border-radius: 4px; }}
#time {{ flex: 1; }}
#error {{ color: #c00; }}
#legend .warning {{ color: #{warning:06x}; font-weight: bold; }}
</style>
</head>
<body>
<div id="view"></div>
<div id="legend"><b>{title}</b>
{rows}
</div>
<div id="controls"><button id="play" type="button">pause</button><input id="time" type="range" min="0" max="1000" value="0" aria-label="time"><span id="clock">0.0 s</span></div>
<script>
/* three.js r187 (https://threejs.org), bundled with GLTFLoader and OrbitControls.
{licence}*/
{three}
</script>
<script id="viaroad-glb" type="application/octet-stream">{glb}</script>
<script>
{viewer}
</script>
</body>
</html>
"#,
        title = escape(title),
        rows = legend_rows(legend),
        warning = super::colour::WARNING,
        three = script(THREE_BUNDLE),
        glb = base64(glb),
        viewer = script(VIEWER),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        // RFC 4648 §10
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
        assert_eq!(base64(&[0xff, 0xfe, 0xfd]), "//79");
    }

    #[test]
    fn page_embeds_everything_and_escapes_the_title() {
        let legend = Legend {
            scene: "a<b>&\"c\"".into(),
            ..Legend::default()
        };
        let p = page(&legend, b"glTF");
        assert!(p.contains("<title>viaroad: a&lt;b&gt;&amp;&quot;c&quot;</title>"));
        assert!(p.contains(">Z2xURg==</script>"));
        // no network: nothing is fetched by URL
        assert!(!p.contains("src=\"http") && !p.contains("<link"));
        // every <script> the page opens is closed once: no `</script` inside a script
        assert_eq!(p.matches("<script").count(), p.matches("</script>").count());
        assert!(p.contains("Permission is hereby granted"));
    }

    #[test]
    fn a_colliding_path_is_a_warning_row_and_lengths_have_no_minus_zero() {
        let plan = super::super::Plan {
            raw: vec![vec![0.0, 0.0], vec![1.0, 0.0]],
            shortened: Vec::new(),
        };
        let mut legend = Legend::default();
        legend.set_paths(&plan, "given path", 1.0, 1.0, Some("collides in segment 1"));
        let rows = legend_rows(&legend);
        assert!(
            rows.contains(r#"<div class="warning">"#)
                && rows.contains("given path — collides in segment 1, length 1.000"),
            "{rows}"
        );
        assert!(!rows.contains("#0967d2"), "{rows}");
        legend.set_paths(&plan, "given path", -0.0, -0.0, None);
        let rows = legend_rows(&legend);
        assert!(
            rows.contains("#0967d2") && rows.contains("given path, length 0.000<"),
            "{rows}"
        );
        assert!(!rows.contains("warning") && !rows.contains("-0"), "{rows}");
        assert_eq!(length(2.5e7), "2.500e7");
    }
}

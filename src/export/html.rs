//! The viewer page: one HTML file with everything inline, so it opens from disk (`file://`)
//! with no network: three.js with its `GLTFLoader` and `OrbitControls` (npm `three`, pinned in
//! `tools/js/package.json`, bundled into `assets/three-bundle.min.js`, MIT licence in
//! `assets/three.LICENSE`), the viewer's own script (`assets/viewer.js`) and the `.glb` as
//! base64.
//!
//! The page exposes `window.viaroad` for tests: `ready`, `error`, `setTime(f)` (f in 0–1 of
//! the animation, pauses it), `only(names)` (draw only the named nodes and what hangs under
//! them; `null` draws all) and `pixels()` (the canvas as base64 RGBA, bottom row first).

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

/// The page showing `glb` (see the module doc); `title` names the scene.
pub fn page(title: &str, glb: &[u8]) -> String {
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
</style>
</head>
<body>
<div id="view"></div>
<div id="legend"><b>{title}</b></div>
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
        let p = page("a<b>&\"c\"", b"glTF");
        assert!(p.contains("<title>viaroad: a&lt;b&gt;&amp;&quot;c&quot;</title>"));
        assert!(p.contains(">Z2xURg==</script>"));
        // no network: nothing is fetched by URL
        assert!(!p.contains("src=\"http") && !p.contains("<link"));
        // every <script> the page opens is closed once: no `</script` inside a script
        assert_eq!(p.matches("<script").count(), p.matches("</script>").count());
        assert!(p.contains("Permission is hereby granted"));
    }
}

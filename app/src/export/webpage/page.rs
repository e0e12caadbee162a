//! The page as HTML text: markup and style, the data ([`super::manifest`]) as JSON, every
//! JavaScript module and every variant's `.glb` as a payload, and the loader that starts the
//! viewer.
//!
//! A payload is a `<script>` element of type [`PAYLOAD_TYPE`] holding the gzip of the bytes in
//! base64: gzip roughly halves mesh data and three.js, base64 keeps the page plain text (a third
//! larger than binary, which HTML cannot carry). The browser inflates it with its own
//! `DecompressionStream`; nothing is executed until the loader has checked every module arrived.
//! Modules come in the order of [`super::three::MODULES`] (`data-module` names each), scenes as
//! `cutaway-scene-<k>` in variant order.
//!
//! Text from the session (title, names) reaches the page only inside JSON (with `<` escaped, so
//! it cannot close the element) and the title element (HTML-escaped); the viewer inserts names
//! as text, never as markup.

use std::io::Write as _;
use std::sync::OnceLock;

use anyhow::Context as _;

use super::VariantPage;
use super::manifest::Manifest;
use super::three::{MODULES, rewritten};

/// The `type` of a payload element.
pub const PAYLOAD_TYPE: &str = "application/x-cutaway-gzip-base64";

const STYLE: &str = include_str!("viewer/page.css");
const BODY: &str = include_str!("viewer/body.html");
const LOADER: &str = include_str!("viewer/loader.js");

/// The page's bytes.
pub fn page_bytes(data: &Manifest, variants: &[VariantPage]) -> anyhow::Result<Vec<u8>> {
    let modules = encoded_modules()
        .as_ref()
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let json = serde_json::to_string(data).context("could not encode the page's data")?;
    let mut html = String::with_capacity(
        modules.iter().map(|(_, m)| m.len()).sum::<usize>()
            + variants.iter().map(|v| v.glb.len()).sum::<usize>()
            + json.len()
            + 64 * 1024,
    );
    html.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    html.push_str(
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1, \
         viewport-fit=cover\">\n",
    );
    html.push_str(&format!(
        "<meta name=\"generator\" content=\"{}\">\n<title>{}</title>\n",
        escape_html(&data.generator),
        escape_html(&data.title)
    ));
    html.push_str("<style>\n");
    html.push_str(STYLE);
    html.push_str("</style>\n</head>\n<body>\n");
    html.push_str(BODY);
    html.push_str("<script type=\"application/json\" id=\"cutaway-data\">");
    html.push_str(&escape_script_json(&json));
    html.push_str("</script>\n");
    html.push_str(&format!(
        "<!-- three.js {} (npm package \"three\"), inlined below in the \"{PAYLOAD_TYPE}\" \
         elements whose data-module names a three.js file:\n\n{}\n-->\n",
        super::three::THREE_VERSION,
        super::three::THREE_LICENSE.trim_end()
    ));
    for (name, payload) in modules {
        html.push_str(&format!(
            "<script type=\"{PAYLOAD_TYPE}\" data-module=\"{name}\">"
        ));
        html.push_str(payload);
        html.push_str("</script>\n");
    }
    for (k, variant) in variants.iter().enumerate() {
        html.push_str(&format!(
            "<script type=\"{PAYLOAD_TYPE}\" id=\"cutaway-scene-{k}\">"
        ));
        html.push_str(&base64(&gzip(&variant.glb)?));
        html.push_str("</script>\n");
    }
    html.push_str("<script>\n");
    html.push_str(LOADER);
    html.push_str("</script>\n</body>\n</html>\n");
    Ok(html.into_bytes())
}

/// Every module of [`MODULES`], rewritten and encoded once per process (they never change).
fn encoded_modules() -> &'static Result<Vec<(&'static str, String)>, String> {
    static MODULES_ENCODED: OnceLock<Result<Vec<(&'static str, String)>, String>> = OnceLock::new();
    MODULES_ENCODED.get_or_init(|| {
        MODULES
            .iter()
            .map(|m| {
                let text = rewritten(m).map_err(|e| format!("{e:#}"))?;
                let zipped = gzip(text.as_bytes()).map_err(|e| format!("{e:#}"))?;
                Ok((m.name, base64(&zipped)))
            })
            .collect()
    })
}

/// `bytes` gzip-compressed.
pub fn gzip(bytes: &[u8]) -> anyhow::Result<Vec<u8>> {
    let mut encoder = flate2::write::GzEncoder::new(
        Vec::with_capacity(bytes.len() / 2),
        flate2::Compression::default(),
    );
    encoder
        .write_all(bytes)
        .and_then(|()| encoder.finish())
        .context("could not compress the page's data")
}

/// Standard base64 (RFC 4648, with padding), as the browser's `atob` reads it.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `text` safe as HTML text or an attribute value.
pub fn escape_html(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// JSON text safe inside a `<script>` element: no `<` (so no `</script>` or `<!--`), written as
/// the JSON escape `\u003c` it stands for.
pub fn escape_script_json(json: &str) -> String {
    json.replace('<', "\\u003c")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_rfc_4648_test_vectors() {
        for (plain, encoded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), encoded, "{plain}");
        }
        assert_eq!(base64(&[0xfb, 0xff, 0xfe]), "+//+");
    }

    #[test]
    fn gzip_round_trips() {
        let bytes: Vec<u8> = (0..10_000u32).flat_map(|i| (i * 7).to_le_bytes()).collect();
        let zipped = gzip(&bytes).unwrap();
        let mut back = Vec::new();
        std::io::Read::read_to_end(&mut flate2::read::GzDecoder::new(&zipped[..]), &mut back)
            .unwrap();
        assert_eq!(back, bytes);
    }

    #[test]
    fn session_text_cannot_close_its_element() {
        let json =
            serde_json::to_string(&serde_json::json!({"name": "</script><script>x()"})).unwrap();
        let safe = escape_script_json(&json);
        assert!(!safe.contains('<'), "{safe}");
        let back: serde_json::Value = serde_json::from_str(&safe).unwrap();
        assert_eq!(back["name"], "</script><script>x()");
        assert_eq!(escape_html("a < b & \"c\""), "a &lt; b &amp; &quot;c&quot;");
    }
}

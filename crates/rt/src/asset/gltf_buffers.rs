//! A glTF's buffers, loaded through [`crate::files::input`] rather than by the `gltf`
//! crate, which opens whatever a URI names (a FIFO blocks it forever, `/dev/zero` reads
//! until memory runs out). External files are read up to their size, and each buffer
//! must hold at least the `byteLength` the document declares.

use std::path::{Path, PathBuf};

/// Where a buffer's URI points on disk, or `None` for an embedded `data:` URI. Relative
/// URIs resolve against `dir`; `file:` URIs name absolute paths.
pub fn buffer_file(dir: &Path, uri: &str) -> Result<Option<PathBuf>, String> {
    if uri.starts_with("data:") {
        return Ok(None);
    }
    if let Some(path) = uri.strip_prefix("file://").or_else(|| uri.strip_prefix("file:")) {
        return Ok(Some(PathBuf::from(percent_decode(path))));
    }
    if uri.contains(':') {
        return Err(format!("buffer URI `{uri}` has a scheme rt cannot read (only files and data: URIs)"));
    }
    Ok(Some(dir.join(percent_decode(uri))))
}

/// Every buffer of `document`: the GLB's binary chunk, an embedded `data:` URI, or a file.
pub fn load(
    document: &gltf::Document,
    dir: &Path,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<gltf::buffer::Data>, String> {
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let i = buffer.index();
        let mut data = match buffer.source() {
            gltf::buffer::Source::Bin => {
                blob.take().ok_or(format!("buffer {i} refers to a missing GLB binary chunk"))?
            }
            gltf::buffer::Source::Uri(uri) => match buffer_file(dir, uri).map_err(|e| format!("buffer {i}: {e}"))? {
                Some(file) => crate::files::read(&file).map_err(|e| format!("buffer {i}: {e}"))?,
                // Decoded in memory: the text is already read, so its size bounds the data.
                None => {
                    gltf::buffer::Data::from_source(buffer.source(), None)
                        .map_err(|e| format!("buffer {i}: bad data URI: {e}"))?
                        .0
                }
            },
        };
        if data.len() < buffer.length() {
            return Err(format!("buffer {i} holds {} bytes but the file declares {}", data.len(), buffer.length()));
        }
        // Accessors read whole 4-byte words, as the gltf crate's own loader pads them.
        data.resize(data.len().next_multiple_of(4), 0);
        buffers.push(gltf::buffer::Data(data));
    }
    Ok(buffers)
}

/// glTF URIs are percent-encoded (RFC 3986); a file name with a space arrives as `%20`.
pub fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        match (bytes[i], bytes.get(i + 1).copied().and_then(hex), bytes.get(i + 2).copied().and_then(hex)) {
            (b'%', Some(hi), Some(lo)) => {
                out.push((hi * 16 + lo) as u8);
                i += 3;
            }
            (b, _, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use crate::asset::fixture::TempDir;
    use crate::asset::gltf_import;

    #[test]
    fn buffers_are_read_safely_and_checked_against_their_declared_length() {
        let dir = TempDir::new("gltf_buffers");
        let gltf = |uri: &str, length: usize| {
            format!(r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {length}, "uri": "{uri}"}}]}}"#)
        };
        let error = |path: std::path::PathBuf| gltf_import::load(&path).expect_err("refused").to_string();
        let zero = dir.write("zero.gltf", &gltf("file:///dev/zero", 36));
        assert!(error(zero).ends_with("zero.gltf: buffer 0: /dev/zero: is a character device, not a file"));
        dir.write("short.bin", "abc");
        let short = dir.write("short.gltf", &gltf("short.bin", 36));
        assert!(error(short).ends_with("buffer 0 holds 3 bytes but the file declares 36"));
        let web = dir.write("web.gltf", &gltf("https://example.com/m.bin", 4));
        assert!(error(web).contains("has a scheme rt cannot read"));
        let bad = || dir.write("bad.gltf", &gltf("%FF%FE.bin", 4));
        // The gltf crate's own loader panics on a URI that decodes to invalid UTF-8.
        assert!(error(bad()).contains("cannot read: No such file"), "{}", error(bad()));
    }
}

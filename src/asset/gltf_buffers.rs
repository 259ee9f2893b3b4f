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
pub fn load(document: &gltf::Document, dir: &Path, mut blob: Option<Vec<u8>>) -> Result<Vec<gltf::buffer::Data>, String> {
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let i = buffer.index();
        let mut data = match buffer.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or(format!("buffer {i} refers to a missing GLB binary chunk"))?,
            gltf::buffer::Source::Uri(uri) => match buffer_file(dir, uri).map_err(|e| format!("buffer {i}: {e}"))? {
                Some(file) => crate::files::read(&file).map_err(|e| format!("buffer {i}: {e}"))?,
                // Decoded in memory: the text is already read, so its size bounds the data.
                None => gltf::buffer::Data::from_source(buffer.source(), None)
                    .map_err(|e| format!("buffer {i}: bad data URI: {e}"))?
                    .0,
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

//! The size headers of inline binary `<DataArray>`s in `.vtu` files, checked before
//! the file is handed to `vtkio` (which trusts them): a header claiming more or fewer
//! bytes than the array holds is an error naming the array and its line.
//!
//! Layout (VTK XML format): a binary array is base64 text of a header (`header_type`
//! UInt32 or UInt64) then the data. Uncompressed, the header is the data's byte count;
//! compressed (`compressor` set), it is `[blocks, block size, last block size, the
//! compressed size of each block]` and the data the compressed blocks. VTK encodes the
//! header and the data separately (two base64 runs), other writers in one run: both are
//! read.

use std::path::Path;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;

use super::error::{IoError, IoResult, Location};

/// How the file's headers are written.
#[derive(Clone, Copy)]
struct Layout {
    /// Bytes per header value (4 or 8).
    size: usize,
    big_endian: bool,
    compressed: bool,
}

impl Layout {
    fn value(&self, bytes: &[u8], k: usize) -> u64 {
        let b = &bytes[k * self.size..(k + 1) * self.size];
        let mut v = 0u64;
        for i in 0..self.size {
            let byte = if self.big_endian { b[i] } else { b[self.size - 1 - i] };
            v = v << 8 | u64::from(byte);
        }
        v
    }
}

/// The base64 characters holding `n` bytes.
fn chars_for(n: usize) -> usize {
    n.div_ceil(3) * 4
}

/// The first `n` bytes of base64 `text`, or None when it is shorter or not base64.
fn decode_prefix(text: &[u8], n: usize) -> Option<Vec<u8>> {
    let chunk = text.get(..chars_for(n))?;
    let bytes = STANDARD.decode(chunk).ok()?;
    (bytes.len() >= n).then(|| bytes[..n].to_vec())
}

/// The data after a header of `header_len` bytes: decoded separately when the header
/// was its own base64 run (padded, or a multiple of 3 bytes), else from the whole text.
fn data_after(text: &[u8], header_len: usize) -> Option<Vec<u8>> {
    let split = chars_for(header_len);
    let padded = text.get(..split)?.ends_with(b"=");
    if padded || header_len.is_multiple_of(3) {
        STANDARD.decode(&text[split..]).ok()
    } else {
        let all = STANDARD.decode(text).ok()?;
        all.get(header_len..).map(<[u8]>::to_vec)
    }
}

/// Checks one array's text; Err is the message.
fn check_array(text: &[u8], layout: Layout) -> Result<(), String> {
    let text: Vec<u8> = text.iter().copied().filter(|b| !b.is_ascii_whitespace()).collect();
    let not_base64 = || "its binary content is not valid base64".to_string();
    let first = decode_prefix(&text, layout.size).ok_or_else(not_base64)?;
    if !layout.compressed {
        let claimed = layout.value(&first, 0);
        let data = data_after(&text, layout.size).ok_or_else(not_base64)?;
        if claimed != data.len() as u64 {
            return Err(format!("its size header says {claimed} bytes, but it holds {}", data.len()));
        }
        return Ok(());
    }
    let blocks = layout.value(&first, 0);
    let header_len = usize::try_from(blocks)
        .ok()
        .and_then(|b| b.checked_add(3)?.checked_mul(layout.size))
        .filter(|&n| chars_for(n) <= text.len())
        .ok_or_else(|| format!("its compression header declares {blocks} blocks, more than the text holds"))?;
    let header = decode_prefix(&text, header_len).ok_or_else(not_base64)?;
    let claimed: u64 = (0..blocks as usize).map(|k| layout.value(&header, 3 + k)).sum();
    let data = data_after(&text, header_len).ok_or_else(not_base64)?;
    if claimed != data.len() as u64 {
        return Err(format!("its compression header says {claimed} compressed bytes, but it holds {}", data.len()));
    }
    Ok(())
}

/// Checks every inline binary DataArray of a `.vtu` file.
///
/// # Errors
/// The first array whose size header does not match its content, at its line.
pub fn check(path: &Path, data: &[u8]) -> IoResult<()> {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_reader(data);
    let mut buf = Vec::new();
    let mut layout = Layout { size: 4, big_endian: false, compressed: false };
    // (line, name) of the binary DataArray whose text comes next.
    let mut open: Option<(usize, String)> = None;
    let line_at = |pos: usize| 1 + data[..pos.min(data.len())].iter().filter(|&&b| b == b'\n').count();
    loop {
        let before = reader.buffer_position() as usize;
        let event = match reader.read_event_into(&mut buf) {
            Ok(e) => e,
            // Syntax errors are vtkio's to report (with their line, see `vtu::read`).
            Err(_) => return Ok(()),
        };
        match event {
            Event::Eof => return Ok(()),
            Event::Start(e) | Event::Empty(e) => {
                let attr = |name: &[u8]| {
                    e.attributes().flatten().find(|a| a.key.as_ref() == name).map(|a| a.value.into_owned())
                };
                match e.name().as_ref() {
                    b"VTKFile" => {
                        layout.size = if attr(b"header_type").as_deref() == Some(b"UInt64") { 8 } else { 4 };
                        layout.big_endian = attr(b"byte_order").as_deref() == Some(b"BigEndian");
                        layout.compressed = attr(b"compressor").is_some_and(|c| !c.is_empty());
                    }
                    b"DataArray" if attr(b"format").as_deref() == Some(b"binary") => {
                        let name = attr(b"Name").map(|n| String::from_utf8_lossy(&n).into_owned()).unwrap_or_default();
                        open = Some((line_at(before), name));
                    }
                    _ => {}
                }
            }
            Event::Text(t) => {
                if let Some((line, name)) = open.take()
                    && let Err(msg) = check_array(t.as_ref(), layout)
                {
                    let what = if name.is_empty() { "a DataArray".to_string() } else { format!("DataArray '{name}'") };
                    return Err(IoError::Parse {
                        path: path.into(),
                        at: Location::Line(line),
                        msg: format!("{what}: {msg}"),
                    });
                }
            }
            Event::End(_) => open = None,
            _ => {}
        }
        buf.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vtu(array: &str) -> String {
        format!(
            "<VTKFile type=\"UnstructuredGrid\">\n<DataArray type=\"Float64\" Name=\"x\" format=\"binary\">{array}</DataArray>\n</VTKFile>\n"
        )
    }

    fn b64(bytes: &[u8]) -> String {
        STANDARD.encode(bytes)
    }

    #[test]
    fn size_headers_must_match_the_data() {
        let data = [7u8; 48];
        // VTK's way (header and data encoded apart) and one run: both accepted.
        let apart = format!("{}{}", b64(&48u32.to_le_bytes()), b64(&data));
        let joint = b64(&[&48u32.to_le_bytes()[..], &data].concat());
        assert!(check(Path::new("a.vtu"), vtu(&apart).as_bytes()).is_ok());
        assert!(check(Path::new("a.vtu"), vtu(&joint).as_bytes()).is_ok());
        for claimed in [8u32, 1_000_000_000] {
            let bad = format!("{}{}", b64(&claimed.to_le_bytes()), b64(&data));
            let e = check(Path::new("a.vtu"), vtu(&bad).as_bytes()).unwrap_err().to_string();
            assert!(e.contains("a.vtu:line 2") && e.contains(&format!("says {claimed} bytes, but it holds 48")), "{e}");
        }
        let e = check(Path::new("a.vtu"), vtu("@@@@").as_bytes()).unwrap_err().to_string();
        assert!(e.contains("not valid base64"), "{e}");
    }
}

//! Loads KTX 2.0 files with libktx (the Khronos Group's KTX-Software library, through the
//! libktx-rs-sys crate's generated bindings: no parsing of ours) and prints one JSON line per
//! file named on the command line:
//!
//!   {"file", "ok", "error", "vk_format", "width", "height", "depth", "levels", "layers", "faces",
//!    "compressed", "supercompression", "oetf", "components", "writer",
//!    "level_bytes": [inflated bytes of each level], "level_fnv1a": [FNV-1a 64 of each, hex]}
//!
//! `ok` is libktx's verdict: the file was created from its name and its image data loaded, which
//! inflates zstd-supercompressed levels (libktx's own zstd) and checks each level's size against
//! the format. `supercompression` is read before the data is loaded (loading inflates it).
//! The FNV-1a digests let a test compare libktx's level bytes with what another reader got.
use libktx_rs_sys::*;
use std::ffi::{CStr, CString};
use std::ptr;

fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf29ce484222325;
    for b in bytes {
        h ^= *b as u64;
        h = h.wrapping_mul(0x100000001b3);
    }
    h
}

fn quoted(s: &str) -> String {
    let mut o = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => o.push_str(&format!("\\u{:04x}", c as u32)),
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

fn error_text(code: ktx_error_code_e) -> String {
    unsafe { CStr::from_ptr(ktxErrorString(code)).to_string_lossy().into_owned() }
}

// The writer's key/value entry (KTXwriter), as libktx read it.
unsafe fn writer(t: *mut ktxTexture2) -> String {
    let key = CString::new("KTXwriter").unwrap();
    let mut len: ktx_uint32_t = 0;
    let mut value: *mut std::os::raw::c_void = ptr::null_mut();
    if ktxHashList_FindValue(&mut (*t).kvDataHead, key.as_ptr(), &mut len, &mut value) != ktx_error_code_e_KTX_SUCCESS
        || value.is_null()
    {
        return String::new();
    }
    let bytes = std::slice::from_raw_parts(value as *const u8, len as usize);
    String::from_utf8_lossy(bytes.split(|b| *b == 0).next().unwrap_or(&[])).into_owned()
}

unsafe fn open(file: &str) -> Result<String, String> {
    let name = CString::new(file).map_err(|_| "a NUL in the name".to_string())?;
    let mut t: *mut ktxTexture2 = ptr::null_mut();
    let rc = ktxTexture2_CreateFromNamedFile(name.as_ptr(), ktxTextureCreateFlagBits_KTX_TEXTURE_CREATE_NO_FLAGS, &mut t);
    if rc != ktx_error_code_e_KTX_SUCCESS {
        return Err(format!("ktxTexture2_CreateFromNamedFile: {}", error_text(rc)));
    }
    let base = t as *mut ktxTexture;
    let vtbl = &*(*t).vtbl;
    let supercompression = (*t).supercompressionScheme;
    let rc = vtbl.LoadImageData.unwrap()(base, ptr::null_mut(), 0);
    let result = if rc != ktx_error_code_e_KTX_SUCCESS {
        Err(format!("ktxTexture_LoadImageData: {}", error_text(rc)))
    } else {
        let data = std::slice::from_raw_parts((*t).pData, (*t).dataSize as usize);
        let (mut sizes, mut digests) = (Vec::new(), Vec::new());
        let mut bad = None;
        for level in 0..(*t).numLevels {
            let size = vtbl.GetImageSize.unwrap()(base, level) as usize;
            let mut offset: ktx_size_t = 0;
            let rc = vtbl.GetImageOffset.unwrap()(base, level, 0, 0, &mut offset);
            let at = offset as usize;
            if rc != ktx_error_code_e_KTX_SUCCESS || at + size > data.len() {
                bad = Some(format!("level {}: no image in the loaded data", level));
                break;
            }
            sizes.push(size.to_string());
            digests.push(format!("\"{:016x}\"", fnv1a(&data[at..at + size])));
        }
        match bad {
            Some(e) => Err(e),
            None => Ok(format!(
                "\"vk_format\": {}, \"width\": {}, \"height\": {}, \"depth\": {}, \"levels\": {}, \"layers\": {}, \
                 \"faces\": {}, \"compressed\": {}, \"supercompression\": {}, \"oetf\": {}, \"components\": {}, \
                 \"writer\": {}, \"level_bytes\": [{}], \"level_fnv1a\": [{}]",
                (*t).vkFormat,
                (*t).baseWidth,
                (*t).baseHeight,
                (*t).baseDepth,
                (*t).numLevels,
                (*t).numLayers,
                (*t).numFaces,
                (*t).isCompressed,
                supercompression,
                ktxTexture2_GetOETF(t),
                ktxTexture2_GetNumComponents(t),
                quoted(&writer(t)),
                sizes.join(", "),
                digests.join(", ")
            )),
        }
    };
    vtbl.Destroy.unwrap()(base);
    result
}

fn main() {
    for file in std::env::args().skip(1) {
        let line = match unsafe { open(&file) } {
            Ok(fields) => format!("{{\"file\": {}, \"ok\": true, \"error\": \"\", {}}}", quoted(&file), fields),
            Err(e) => format!("{{\"file\": {}, \"ok\": false, \"error\": {}}}", quoted(&file), quoted(&e)),
        };
        println!("{}", line);
    }
}

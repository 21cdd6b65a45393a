//! NumPy `.npz` output: a zip archive of `.npy` arrays, stored
//! uncompressed. Nothing in the dependency tree writes zip files, and the
//! stored (method 0) subset of the format is small: a local header before
//! each file, a central directory, an end record (PKWARE APPNOTE 6.3.x,
//! sections 4.3.7, 4.3.12, 4.3.16), with each file's CRC-32.

use crate::common::{CliError, CliResult};

/// One array: its `.npy` dtype (`<f8`, `|u1`, `|i1`, `<i8`, `<U..`), shape and
/// little-endian bytes.
pub struct Array {
    /// Entry name without `.npy`.
    pub name: String,
    /// NumPy dtype string.
    pub descr: String,
    /// Shape (empty for a scalar).
    pub shape: Vec<usize>,
    /// The data, C order, little-endian.
    pub bytes: Vec<u8>,
}

impl Array {
    /// A float64 array.
    pub fn f64(name: &str, shape: Vec<usize>, values: &[f64]) -> Array {
        Array {
            name: name.into(),
            descr: "<f8".into(),
            shape,
            bytes: values.iter().flat_map(|v| v.to_le_bytes()).collect(),
        }
    }

    /// A uint8 array.
    pub fn u8(name: &str, shape: Vec<usize>, values: &[u8]) -> Array {
        Array {
            name: name.into(),
            descr: "|u1".into(),
            shape,
            bytes: values.to_vec(),
        }
    }

    /// An int8 array.
    pub fn i8(name: &str, shape: Vec<usize>, values: &[i8]) -> Array {
        Array {
            name: name.into(),
            descr: "|i1".into(),
            shape,
            bytes: values.iter().map(|&v| v as u8).collect(),
        }
    }

    /// A scalar string (NumPy's `<U` dtype: UTF-32 code points).
    pub fn text(name: &str, value: &str) -> Array {
        let chars = value.chars().count().max(1);
        let mut bytes: Vec<u8> = value
            .chars()
            .flat_map(|c| (c as u32).to_le_bytes())
            .collect();
        bytes.resize(4 * chars, 0);
        Array {
            name: name.into(),
            descr: format!("<U{chars}"),
            shape: vec![],
            bytes,
        }
    }

    /// An int64 array.
    pub fn i64(name: &str, shape: Vec<usize>, values: &[i64]) -> Array {
        Array {
            name: name.into(),
            descr: "<i8".into(),
            shape,
            bytes: values.iter().flat_map(|v| v.to_le_bytes()).collect(),
        }
    }

    /// The `.npy` file (format 1.0): magic, header length, a Python-literal
    /// header dict padded with spaces to a multiple of 64 bytes, the data.
    fn npy(&self) -> Vec<u8> {
        let shape = match self.shape.len() {
            0 => "()".to_string(),
            1 => format!("({},)", self.shape[0]),
            _ => format!(
                "({})",
                self.shape
                    .iter()
                    .map(|s| s.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        let mut header = format!(
            "{{'descr': '{}', 'fortran_order': False, 'shape': {shape}, }}",
            self.descr
        );
        while (10 + header.len() + 1) % 64 != 0 {
            header.push(' ');
        }
        header.push('\n');
        let mut out = Vec::with_capacity(10 + header.len() + self.bytes.len());
        out.extend_from_slice(b"\x93NUMPY\x01\x00");
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        out.extend_from_slice(&self.bytes);
        out
    }
}

/// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), as zip requires.
fn crc32(data: &[u8]) -> u32 {
    let mut table = [0u32; 256];
    for (i, entry) in table.iter_mut().enumerate() {
        let mut c = i as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
        *entry = c;
    }
    !data.iter().fold(!0u32, |c, &b| {
        table[((c ^ b as u32) & 0xFF) as usize] ^ (c >> 8)
    })
}

/// The `.npz` bytes of `arrays`. Errors: an archive past zip's 4 GiB
/// limits (no zip64).
pub fn npz(arrays: &[Array]) -> CliResult<Vec<u8>> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    let too_large = || {
        CliError("the map is larger than a zip file without zip64 holds (4 GiB): choose a coarser resolution or fewer orientations".into())
    };
    for array in arrays {
        let data = array.npy();
        let name = format!("{}.npy", array.name);
        let size = u32::try_from(data.len()).map_err(|_| too_large())?;
        let offset = u32::try_from(out.len()).map_err(|_| too_large())?;
        let crc = crc32(&data);
        // Version 2.0, no flags, stored, time 00:00, date 1980-01-01.
        let common = |v: &mut Vec<u8>| {
            v.extend_from_slice(&20u16.to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes());
            v.extend_from_slice(&0x21u16.to_le_bytes());
            v.extend_from_slice(&crc.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&(name.len() as u16).to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes());
        };
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        common(&mut out);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&data);
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&20u16.to_le_bytes());
        common(&mut central);
        // Comment length, disk, internal and external attributes, offset.
        central.extend_from_slice(&[0u8; 6]);
        central.extend_from_slice(&0u32.to_le_bytes());
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let directory_offset = u32::try_from(out.len()).map_err(|_| too_large())?;
    let count = arrays.len() as u16;
    out.extend_from_slice(&central);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0u8; 4]);
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&(central.len() as u32).to_le_bytes());
    out.extend_from_slice(&directory_offset.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    Ok(out)
}

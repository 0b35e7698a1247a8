//! Accessors: POSITION, NORMAL, TEXCOORD and index data, every count, offset and stride checked
//! against its buffer view and buffer before it is read; sparse substitution; every float
//! finite.

use glam::DVec3;
use gltf::json;
use json::validation::Checked;

use super::document::{Document, invalid};
use crate::error::GltfError;

impl Document {
    /// Reads a FLOAT VEC3 accessor (`attribute`: POSITION or NORMAL) as f64 points, every
    /// component finite.
    pub(crate) fn read_vec3(
        &mut self,
        index: usize,
        attribute: &'static str,
    ) -> Result<Vec<DVec3>, GltfError> {
        let (acc, comp) = self.accessor_layout(index, self.limits.max_positions)?;
        if acc.mult != 3 || comp != json::accessor::ComponentType::F32 {
            return Err(invalid(
                "accessor",
                index,
                format!(
                    "{attribute} must be FLOAT VEC3, found {comp:?} with {} components",
                    acc.mult
                ),
            ));
        }
        let values = self.read_components(index, &acc, comp)?;
        check_finite(&values, 3, index, attribute)?;
        Ok(values
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect())
    }

    /// Reads a TEXCOORD accessor (VEC2 FLOAT, or normalized UNSIGNED_BYTE/SHORT).
    pub(crate) fn read_texcoords(&mut self, index: usize) -> Result<Vec<[f32; 2]>, GltfError> {
        use json::accessor::ComponentType as C;
        let (acc, comp) = self.accessor_layout(index, self.limits.max_positions)?;
        let normalized = self.root.accessors[index].normalized;
        let scale = match comp {
            C::F32 => 1.0,
            C::U8 if normalized => 1.0 / 255.0,
            C::U16 if normalized => 1.0 / 65535.0,
            _ => 0.0,
        };
        if acc.mult != 2 || scale == 0.0 {
            return Err(invalid(
                "accessor",
                index,
                format!(
                    "TEXCOORD must be VEC2 FLOAT or normalized UNSIGNED_BYTE/SHORT, found \
                     {comp:?} with {} components",
                    acc.mult
                ),
            ));
        }
        let values = self.read_components(index, &acc, comp)?;
        check_finite(&values, 2, index, "TEXCOORD_0")?;
        Ok(values
            .chunks_exact(2)
            .map(|c| [(c[0] * scale) as f32, (c[1] * scale) as f32])
            .collect())
    }

    /// Reads an index accessor (SCALAR, UNSIGNED_BYTE/SHORT/INT).
    pub(crate) fn read_indices(&mut self, index: usize) -> Result<Vec<u32>, GltfError> {
        use json::accessor::ComponentType as C;
        let limit = self.limits.max_triangles.saturating_mul(3);
        let (acc, comp) = self.accessor_layout(index, limit)?;
        if acc.mult != 1 || !matches!(comp, C::U8 | C::U16 | C::U32) {
            return Err(invalid(
                "accessor",
                index,
                format!(
                    "indices must be SCALAR UNSIGNED_BYTE/SHORT/INT, found {comp:?} with {} components",
                    acc.mult
                ),
            ));
        }
        // Integers up to 2^32 are exact in f64.
        Ok(self
            .read_components(index, &acc, comp)?
            .into_iter()
            .map(|x| x as u32)
            .collect())
    }

    fn accessor_layout(
        &self,
        index: usize,
        limit: usize,
    ) -> Result<(Layout, json::accessor::ComponentType), GltfError> {
        let acc = self.root.accessors.get(index).ok_or_else(|| {
            invalid(
                "accessor",
                index,
                format!("does not exist ({} accessors)", self.root.accessors.len()),
            )
        })?;
        let comp = match acc.component_type {
            Checked::Valid(c) => c.0,
            Checked::Invalid => return Err(invalid("accessor", index, "invalid componentType")),
        };
        let mult = match acc.type_ {
            Checked::Valid(t) => t.multiplicity(),
            Checked::Invalid => return Err(invalid("accessor", index, "invalid type")),
        };
        if acc.count.0 > limit as u64 {
            return Err(invalid(
                "accessor",
                index,
                format!("count {} is above the input limit of {limit}", acc.count.0),
            ));
        }
        Ok((
            Layout {
                count: acc.count.0 as usize,
                mult,
            },
            comp,
        ))
    }

    /// Components of every element of accessor `index` as f64 (`count × mult` values), with
    /// sparse substitution applied.
    fn read_components(
        &mut self,
        index: usize,
        layout: &Layout,
        comp: json::accessor::ComponentType,
    ) -> Result<Vec<f64>, GltfError> {
        let acc = self.root.accessors[index].clone();
        let Layout { count, mult } = *layout;
        let elem = comp.size() * mult;
        let mut out = match acc.buffer_view {
            None => vec![0.0; count * mult],
            Some(view) => {
                let offset = acc.byte_offset.map_or(0, |o| o.0);
                let (bytes, stride) = self.view_bytes(view.value(), index, elem)?;
                read_strided(bytes, offset, stride, count, elem, comp, mult)
                    .map_err(|r| invalid("accessor", index, r))?
            }
        };
        if let Some(sparse) = &acc.sparse {
            let n = sparse.count.0;
            if n == 0 || n > count as u64 {
                return Err(invalid(
                    "accessor",
                    index,
                    format!("sparse count {n} must be in 1..={count}"),
                ));
            }
            let n = n as usize;
            let icomp = match sparse.indices.component_type {
                Checked::Valid(c) => c.0,
                Checked::Invalid => {
                    return Err(invalid("accessor", index, "invalid sparse index type"));
                }
            };
            let (ibytes, _) = self.view_bytes(sparse.indices.buffer_view.value(), index, 1)?;
            let ibytes = ibytes.to_vec();
            let positions = read_strided(
                &ibytes,
                sparse.indices.byte_offset.0,
                icomp.size(),
                n,
                icomp.size(),
                icomp,
                1,
            )
            .map_err(|r| invalid("accessor", index, format!("sparse indices: {r}")))?;
            let (vbytes, _) = self.view_bytes(sparse.values.buffer_view.value(), index, 1)?;
            let values = read_strided(
                vbytes,
                sparse.values.byte_offset.0,
                elem,
                n,
                elem,
                comp,
                mult,
            )
            .map_err(|r| invalid("accessor", index, format!("sparse values: {r}")))?;
            for (k, &p) in positions.iter().enumerate() {
                let p = p as usize;
                if p >= count {
                    return Err(invalid(
                        "accessor",
                        index,
                        format!("sparse index {p} is not below count {count}"),
                    ));
                }
                out[p * mult..(p + 1) * mult].copy_from_slice(&values[k * mult..(k + 1) * mult]);
            }
        }
        Ok(out)
    }

    /// The bytes of buffer view `view` and its stride (`byteStride`, or `elem` if absent).
    fn view_bytes(
        &mut self,
        view: usize,
        accessor: usize,
        elem: usize,
    ) -> Result<(&[u8], usize), GltfError> {
        let v = self.root.buffer_views.get(view).cloned().ok_or_else(|| {
            invalid(
                "accessor",
                accessor,
                format!(
                    "bufferView {view} does not exist ({} views)",
                    self.root.buffer_views.len()
                ),
            )
        })?;
        let stride = v.byte_stride.map_or(elem, |s| s.0);
        if stride < elem {
            return Err(invalid(
                "bufferView",
                view,
                format!(
                    "byteStride {stride} is smaller than the element size {elem} of accessor {accessor}"
                ),
            ));
        }
        let data = self.buffer(v.buffer.value())?;
        let start = v.byte_offset.map_or(0, |o| o.0);
        let end = start.checked_add(v.byte_length.0);
        match end {
            Some(end) if end <= data.len() as u64 => {
                Ok((&data[start as usize..end as usize], stride))
            }
            _ => Err(invalid(
                "bufferView",
                view,
                format!(
                    "bytes {start}+{} lie beyond its buffer's {} bytes",
                    v.byte_length.0,
                    data.len()
                ),
            )),
        }
    }
}

/// `Err(GltfError::NonFinite)` naming the first element (of `mult` components) of accessor
/// `accessor` with a NaN or infinite component.
fn check_finite(
    values: &[f64],
    mult: usize,
    accessor: usize,
    attribute: &'static str,
) -> Result<(), GltfError> {
    match values.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(GltfError::NonFinite {
            accessor,
            attribute,
            element: i / mult,
        }),
        None => Ok(()),
    }
}

#[derive(Clone, Copy)]
struct Layout {
    count: usize,
    mult: usize,
}

/// `count` elements of `mult` components each, the first at `offset`, `stride` bytes apart.
fn read_strided(
    bytes: &[u8],
    offset: u64,
    stride: usize,
    count: usize,
    elem: usize,
    comp: json::accessor::ComponentType,
    mult: usize,
) -> Result<Vec<f64>, String> {
    use json::accessor::ComponentType as C;
    if count == 0 {
        return Ok(Vec::new());
    }
    let last_end = (stride as u64)
        .checked_mul(count as u64 - 1)
        .and_then(|x| x.checked_add(offset))
        .and_then(|x| x.checked_add(elem as u64));
    match last_end {
        Some(e) if e <= bytes.len() as u64 => {}
        _ => {
            return Err(format!(
                "{count} elements of {elem} bytes (stride {stride}, offset {offset}) do not fit in \
                 its buffer view of {} bytes",
                bytes.len()
            ));
        }
    }
    let size = comp.size();
    let mut out = Vec::with_capacity(count * mult);
    for i in 0..count {
        let at = offset as usize + i * stride;
        for k in 0..mult {
            let b = &bytes[at + k * size..at + (k + 1) * size];
            out.push(match comp {
                C::I8 => f64::from(b[0] as i8),
                C::U8 => f64::from(b[0]),
                C::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
                C::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
                C::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                C::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strided_reads_check_the_last_element() {
        use json::accessor::ComponentType as C;
        let bytes = [0u8; 24];
        assert!(read_strided(&bytes, 0, 12, 2, 12, C::F32, 3).is_ok());
        assert!(read_strided(&bytes, 4, 12, 2, 12, C::F32, 3).is_err());
        assert!(read_strided(&bytes, u64::MAX, 12, 2, 12, C::F32, 3).is_err());
        assert!(read_strided(&bytes, 0, usize::MAX, 3, 12, C::F32, 3).is_err());
    }
}

//! Randomness and the structure-aware mutations of each target kind.

use facebem::{FaceModel, cache};

/// xorshift64* generator.
pub(crate) struct Rng(pub(crate) u64);
impl Rng {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub(crate) fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
    pub(crate) fn chance(&mut self, one_in: usize) -> bool {
        self.below(one_in) == 0
    }
}

const SPECIAL: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1",
    "2",
    "3",
    "0.5",
    "1e300",
    "-1e300",
    "1e-300",
    "nan",
    "inf",
    "-inf",
    "255",
    "65535",
    "65536",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "18446744073709551615",
    "1099511627776",
    "4611686018427387904",
    "100000",
    "1e9",
    "7",
];

/// Byte-level mutations of any input.
fn mutate_bytes(r: &mut Rng, data: &mut Vec<u8>) {
    if data.is_empty() {
        data.push(r.next() as u8);
        return;
    }
    let n = data.len();
    match r.below(6) {
        0 => {
            let i = r.below(n);
            data[i] ^= 1 << r.below(8);
        }
        1 => {
            let i = r.below(n);
            data[i] = [0, 0xFF, 0x7F, 0x80, b'-', b'9', b'[', b'"'][r.below(8)];
        }
        2 => data.truncate(r.below(n)),
        3 => {
            let (a, len) = (r.below(n), 1 + r.below(64));
            let end = (a + len).min(n);
            data.drain(a..end);
        }
        4 => {
            let (a, len) = (r.below(n), 1 + r.below(256));
            let piece = data[a..(a + len).min(n)].to_vec();
            let at = r.below(n);
            data.splice(at..at, piece);
        }
        _ => {
            let at = r.below(n);
            let junk: Vec<u8> = (0..1 + r.below(16)).map(|_| r.next() as u8).collect();
            data.splice(at..at, junk);
        }
    }
}

/// Line- and number-level mutations of a text input (OBJ, muscle file).
pub(crate) fn mutate_text(r: &mut Rng, text: &str) -> Vec<u8> {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    for _ in 0..1 + r.below(3) {
        if lines.is_empty() {
            lines.push(String::new());
        }
        let i = r.below(lines.len());
        match r.below(7) {
            0 => {
                let j = r.below(lines.len());
                lines.swap(i, j);
            }
            1 => {
                let l = lines[i].clone();
                let copies = if r.chance(8) { 1 + r.below(5000) } else { 1 };
                for _ in 0..copies {
                    lines.insert(i, l.clone());
                }
            }
            2 => {
                lines.remove(i);
            }
            _ => {
                // Replace one whitespace-separated token with a special number.
                let mut words: Vec<String> = lines[i].split(' ').map(str::to_owned).collect();
                let w = r.below(words.len());
                words[w] = SPECIAL[r.below(SPECIAL.len())].to_owned();
                if r.chance(4) && w > 0 {
                    words[w] = format!("{}/{}", words[w], SPECIAL[r.below(SPECIAL.len())]);
                }
                lines[i] = words.join(" ");
            }
        }
    }
    let mut out = lines.join("\n").into_bytes();
    if r.chance(10) {
        mutate_bytes(r, &mut out);
    }
    out
}

/// Mutates one value of a JSON document (structure-aware glTF mutation).
fn mutate_json(r: &mut Rng, v: &mut serde_json::Value) {
    use serde_json::Value;
    // Collect paths to every value, pick one.
    fn count(v: &Value) -> usize {
        1 + match v {
            Value::Array(a) => a.iter().map(count).sum(),
            Value::Object(o) => o.values().map(count).sum(),
            _ => 0,
        }
    }
    fn nth(v: &mut Value, mut k: usize) -> Option<&mut Value> {
        if k == 0 {
            return Some(v);
        }
        k -= 1;
        let children: Vec<&mut Value> = match v {
            Value::Array(a) => a.iter_mut().collect(),
            Value::Object(o) => o.values_mut().collect(),
            _ => return None,
        };
        for c in children {
            let n = count(c);
            if k < n {
                return nth(c, k);
            }
            k -= n;
        }
        None
    }
    let total = count(v);
    let k = r.below(total);
    let choice = r.below(10);
    let Some(target) = nth(v, k) else { return };
    let special = SPECIAL[r.below(SPECIAL.len())];
    match (choice, &mut *target) {
        (0..=4, Value::Number(_)) | (0..=1, Value::Bool(_)) => {
            *target = serde_json::from_str(special).unwrap_or(Value::Null);
        }
        (_, Value::Array(a)) if !a.is_empty() => match r.below(3) {
            0 => {
                a.remove(r.below(a.len()));
            }
            1 => {
                let x = a[r.below(a.len())].clone();
                a.push(x);
            }
            _ => a.push(serde_json::json!(r.below(4))),
        },
        (_, Value::Object(o)) if !o.is_empty() => {
            let keys: Vec<String> = o.keys().cloned().collect();
            let key = &keys[r.below(keys.len())];
            match r.below(4) {
                0 => {
                    o.remove(key);
                }
                1 => {
                    o.insert("children".into(), serde_json::json!([r.below(3)]));
                }
                2 => {
                    let uris = [
                        "../face.bin",
                        "/etc/passwd",
                        "file:///dev/zero",
                        "%FF",
                        "face.bin",
                        "fifo.bin",
                        "data:x;base64,AAAA",
                        "sub/../face.bin",
                        "face%2Ebin",
                        "C:x",
                    ];
                    o.insert("uri".into(), serde_json::json!(uris[r.below(uris.len())]));
                }
                _ => {
                    let fields = [
                        "byteStride",
                        "byteOffset",
                        "count",
                        "componentType",
                        "sparse",
                        "mode",
                        "indices",
                        "mesh",
                        "scene",
                        "byteLength",
                        "bufferView",
                        "buffer",
                    ];
                    let f = fields[r.below(fields.len())];
                    let val = if f == "sparse" {
                        serde_json::json!({"count": serde_json::from_str::<Value>(special).unwrap_or(Value::Null),
                            "indices": {"bufferView": 1, "componentType": 5125},
                            "values": {"bufferView": 0}})
                    } else {
                        serde_json::from_str(special).unwrap_or(Value::Null)
                    };
                    o.insert(f.into(), val);
                }
            }
        }
        (_, Value::String(s)) => *s = special.to_owned(),
        _ => *target = serde_json::from_str(special).unwrap_or(Value::Null),
    }
}

pub(crate) fn mutate_gltf(r: &mut Rng, seed: &[u8]) -> Vec<u8> {
    if seed.starts_with(b"glTF") && seed.len() > 20 {
        // GLB: mutate its JSON chunk (structure-aware) or its bytes.
        let jlen = u32::from_le_bytes([seed[12], seed[13], seed[14], seed[15]]) as usize;
        if r.chance(2) && 20 + jlen <= seed.len() {
            let mut v: serde_json::Value = match serde_json::from_slice(&seed[20..20 + jlen]) {
                Ok(v) => v,
                Err(_) => return seed.to_vec(),
            };
            for _ in 0..1 + r.below(3) {
                mutate_json(r, &mut v);
            }
            let mut j = serde_json::to_vec(&v).unwrap_or_default();
            while !j.len().is_multiple_of(4) {
                j.push(b' ');
            }
            let rest = &seed[20 + jlen..];
            let mut out = seed[..12].to_vec();
            out.extend_from_slice(&(j.len() as u32).to_le_bytes());
            out.extend_from_slice(b"JSON");
            out.extend_from_slice(&j);
            out.extend_from_slice(rest);
            let total = out.len() as u32;
            out[8..12].copy_from_slice(&total.to_le_bytes());
            return out;
        }
        let mut out = seed.to_vec();
        mutate_bytes(r, &mut out);
        return out;
    }
    match serde_json::from_slice::<serde_json::Value>(seed) {
        Ok(mut v) if !r.chance(5) => {
            for _ in 0..1 + r.below(3) {
                mutate_json(r, &mut v);
            }
            serde_json::to_vec(&v).unwrap_or_default()
        }
        _ => {
            let mut out = seed.to_vec();
            mutate_bytes(r, &mut out);
            out
        }
    }
}

/// Rig mutations: bytes of the payload with the checksum and hashes recomputed, or one field
/// of the decoded model changed and re-encoded.
pub(crate) fn mutate_rig(r: &mut Rng, seed: &[u8], model: &FaceModel) -> Vec<u8> {
    const HEADER: usize = 116;
    if r.chance(2) {
        let mut m = model.clone();
        let f = r.below(9);
        let pick = |r: &mut Rng, len: usize| r.below(len.max(1));
        let special: f64 = SPECIAL[r.below(SPECIAL.len())].parse().unwrap_or(f64::NAN);
        match f {
            0 => {
                let i = pick(r, m.basis.neutral.len());
                if let Some(p) = m.basis.neutral.get_mut(i) {
                    p.x = special;
                }
            }
            1 => {
                let k = pick(r, m.basis.displacements.len());
                if let Some(d) = m.basis.displacements.get_mut(k) {
                    if r.chance(2) {
                        d.truncate(pick(r, d.len()))
                    } else if let Some(p) = d.first_mut() {
                        p.z = special
                    }
                }
            }
            2 => {
                m.basis
                    .muscle_ids
                    .truncate(pick(r, m.basis.muscle_ids.len()));
            }
            3 => {
                let k = pick(r, m.rig.muscles.len());
                if let Some(mu) = m.rig.muscles.get_mut(k) {
                    mu.front_chain.push(r.next() as u32);
                }
            }
            4 => {
                let t = pick(r, m.mesh.triangles.len());
                if let Some(tri) = m.mesh.triangles.get_mut(t) {
                    tri[r.below(3)] = r.next() as u32 % 1000;
                }
            }
            5 => m.params.poisson = special,
            6 => m
                .rig
                .shell
                .triangles
                .truncate(pick(r, m.rig.shell.triangles.len())),
            7 => m.rig.skull.push(r.next() as u32 % 5000),
            _ => {
                if let Some(t) = &mut m.obj_source {
                    t.push_str("\nv 1 2 3\n");
                }
            }
        }
        return cache::to_bytes(&m).unwrap_or_default();
    }
    let mut out = seed.to_vec();
    if out.len() > HEADER && !r.chance(10) {
        let mut body = out[HEADER..].to_vec();
        for _ in 0..1 + r.below(4) {
            mutate_bytes(r, &mut body);
        }
        out.truncate(HEADER);
        out[76..84].copy_from_slice(&(body.len() as u64).to_le_bytes());
        out[84..116].copy_from_slice(blake3::hash(&body).as_bytes());
        out.extend_from_slice(&body);
    } else {
        mutate_bytes(r, &mut out);
    }
    out
}

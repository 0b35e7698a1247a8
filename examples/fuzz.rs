//! Structure-aware mutation fuzzer of facebem's input readers, on stable Rust.
//!
//! ```text
//! cargo run --release --example fuzz -- --minutes 30 --target obj|gltf|rig|muscles \
//!     [--out DIR] [--seed N] [--case-seconds 5] [--hang-seconds 60] [--case-mb 500]
//! ```
//!
//! Time is CPU time on Linux (from `/proc`): `--minutes` is the workers' CPU time, and a case
//! is slow when it uses more than `--case-seconds` of CPU, so a loaded machine does not turn
//! starvation into findings; a case that blocks without using CPU (a FIFO, a lock) is caught
//! by the wall-clock `--hang-seconds`. Workers run with `RAYON_NUM_THREADS=1` unless it is set,
//! i.e. on one core. Elsewhere both fall back to wall-clock time.
//!
//! A supervisor process runs worker processes (this binary with `--worker`) until the time is
//! up. A worker mutates the bundled MediaPipe face as the target kind (OBJ text lines and
//! numbers; glTF JSON fields, URIs and GLB bytes; rig payloads with recomputed checksums, and
//! decoded rigs with one field changed; muscle file lines and numbers) and runs each case in a
//! thread under `catch_unwind`, with a time limit and a memory limit (a counting allocator that
//! refuses allocations beyond it, which aborts the worker). Before each case the input is written
//! to `DIR/inflight.EXT`; a panic is saved as `DIR/panic-HASH.EXT` (+ `.txt` message), a case
//! over the time limit as `DIR/slow-HASH.EXT` (the worker then exits and is restarted), and an
//! abort (memory limit, stack overflow) as `DIR/crash-N.EXT` by the supervisor. Valid meshes
//! also go through the rig prep (`facebem::prep_rig`), valid rigs through posing and both
//! exports, valid muscle files through `FaceRig::with_muscles`. The summary (cases, failures,
//! slowest case, largest per-case peak of live heap) is printed and written to
//! `DIR/summary.txt`. Every finding belongs in `tests/bad_inputs/` with its expected error.
#![allow(unsafe_code)] // the counting global allocator below

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::time::{Duration, Instant};

use facebem::face_prep::{self, FaceMesh, muscle_file};
use facebem::{Control, FaceModel, PipelineParams, cache};

// ---------------------------------------------------------------- memory accounting

struct Counting;
static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static LIMIT: AtomicUsize = AtomicUsize::new(usize::MAX);

fn grow(by: usize) -> bool {
    let now = LIVE.fetch_add(by, Relaxed) + by;
    if now > LIMIT.load(Relaxed) {
        LIVE.fetch_sub(by, Relaxed);
        return false;
    }
    PEAK.fetch_max(now, Relaxed);
    true
}

// SAFETY: every method forwards to the system allocator with the caller's arguments; the
// counters only decide whether to forward an allocation at all (returning null is allowed).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        if !grow(l.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded unchanged.
        unsafe { System.alloc(l) }
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        if !grow(l.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded unchanged.
        unsafe { System.alloc_zeroed(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size(), Relaxed);
        // SAFETY: forwarded unchanged.
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        if new > l.size() && !grow(new - l.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded unchanged.
        let r = unsafe { System.realloc(p, l, new) };
        if r.is_null() {
            if new > l.size() {
                LIVE.fetch_sub(new - l.size(), Relaxed);
            }
        } else if new < l.size() {
            LIVE.fetch_sub(l.size() - new, Relaxed);
        }
        r
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

// ---------------------------------------------------------------- options, randomness

#[derive(Clone)]
struct Opts {
    minutes: f64,
    target: String,
    out: PathBuf,
    seed: u64,
    case_seconds: f64,
    hang_seconds: f64,
    case_mb: usize,
    worker: bool,
}

fn parse_opts() -> Result<Opts, String> {
    let mut o = Opts {
        minutes: 1.0,
        target: "obj".into(),
        out: PathBuf::new(),
        seed: 1,
        case_seconds: 5.0,
        hang_seconds: 60.0,
        case_mb: 500,
        worker: false,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut val = || args.next().ok_or(format!("{a} needs a value"));
        match a.as_str() {
            "--minutes" => o.minutes = val()?.parse().map_err(|e| format!("--minutes: {e}"))?,
            "--target" => o.target = val()?,
            "--out" => o.out = PathBuf::from(val()?),
            "--seed" => o.seed = val()?.parse().map_err(|e| format!("--seed: {e}"))?,
            "--case-seconds" => o.case_seconds = val()?.parse().map_err(|e| format!("{e}"))?,
            "--hang-seconds" => o.hang_seconds = val()?.parse().map_err(|e| format!("{e}"))?,
            "--case-mb" => o.case_mb = val()?.parse().map_err(|e| format!("{e}"))?,
            "--worker" => o.worker = true,
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if !["obj", "gltf", "rig", "muscles"].contains(&o.target.as_str()) {
        return Err(format!("--target {} (obj, gltf, rig or muscles)", o.target));
    }
    if o.out.as_os_str().is_empty() {
        o.out = std::env::temp_dir().join(format!("facebem-fuzz-{}", o.target));
    }
    Ok(o)
}

/// CPU seconds of this process (`self_` true: its own threads) or of its waited-for children
/// (`self_` false), from `/proc/self/stat` (clock ticks of 1/100 s, Linux's USER_HZ).
fn cpu_seconds(self_: bool) -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name "(…)": state is field 3, utime 14, stime 15, cutime 16,
    // cstime 17 (proc(5)).
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split(' ').collect();
    let (a, b) = if self_ { (11, 12) } else { (13, 14) };
    let ticks = f.get(a)?.parse::<f64>().ok()? + f.get(b)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// A clock of CPU seconds ([`cpu_seconds`]), or of wall-clock seconds where `/proc` is missing.
struct Clock {
    self_: bool,
    cpu0: Option<f64>,
    wall0: Instant,
}

impl Clock {
    fn start(self_: bool) -> Clock {
        Clock {
            self_,
            cpu0: cpu_seconds(self_),
            wall0: Instant::now(),
        }
    }
    /// CPU seconds since `start` (wall-clock seconds without `/proc`).
    fn cpu(&self) -> f64 {
        match (self.cpu0, cpu_seconds(self.self_)) {
            (Some(a), Some(b)) => b - a,
            _ => self.wall(),
        }
    }
    fn wall(&self) -> f64 {
        self.wall0.elapsed().as_secs_f64()
    }
}

/// xorshift64* generator.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
    fn chance(&mut self, one_in: usize) -> bool {
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

// ---------------------------------------------------------------- seeds and mutations

fn face_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/mediapipe_canonical_4loop.obj")
}

fn ext(target: &str, case: &[u8]) -> &'static str {
    match target {
        "obj" => "obj",
        "gltf" if case.starts_with(b"glTF") => "glb",
        "gltf" => "gltf",
        "rig" => "rig",
        _ => "muscles",
    }
}

/// One GLB (positions f32, indices u32) of a face mesh, plus a .gltf with a data URI and one
/// with an external `face.bin`.
fn gltf_seeds(face: &FaceMesh) -> (Vec<u8>, String, String, Vec<u8>) {
    let mut bin = Vec::new();
    for p in &face.vertices {
        for c in p.to_array() {
            bin.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    let pos_len = bin.len();
    for t in &face.triangles {
        for i in t {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let json = |uri: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"children":[1]}},{{"mesh":0,"scale":[1,1,1]}}],"meshes":[{{"name":"face","primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"mode":4}}]}}],"buffers":[{{{uri}"byteLength":{}}}],"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{pos_len},"byteStride":12}},{{"buffer":0,"byteOffset":{pos_len},"byteLength":{}}}],"accessors":[{{"bufferView":0,"byteOffset":0,"componentType":5126,"count":{},"type":"VEC3","min":[-9,-9,-9],"max":[9,9,9]}},{{"bufferView":1,"componentType":5125,"count":{},"type":"SCALAR"}}]}}"#,
            bin.len(),
            bin.len() - pos_len,
            face.vertices.len(),
            face.triangles.len() * 3
        )
    };
    let mut j = json("").into_bytes();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut glb = b"glTF".to_vec();
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&((12 + 8 + j.len() + 8 + bin.len()) as u32).to_le_bytes());
    glb.extend_from_slice(&(j.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&j);
    glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    let b64 = base64(&bin);
    let data = json(&format!(
        r#""uri":"data:application/octet-stream;base64,{b64}","#
    ));
    let external = json(r#""uri":"face.bin","#);
    (glb, data, external, bin)
}

fn base64(b: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in b.chunks(3) {
        let v = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            s.push(if k <= c.len() {
                T[(v >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    s
}

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
fn mutate_text(r: &mut Rng, text: &str) -> Vec<u8> {
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

fn mutate_gltf(r: &mut Rng, seed: &[u8]) -> Vec<u8> {
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
fn mutate_rig(r: &mut Rng, seed: &[u8], model: &FaceModel) -> Vec<u8> {
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

// ---------------------------------------------------------------- running a case

struct Ctx {
    target: String,
    work: PathBuf,
    model: Option<FaceModel>,
    element_count: usize,
}

/// Runs one case; `Err` is an oracle failure (a wrong result rather than a refusal).
fn run_case(ctx: &Ctx, data: &[u8], deep: bool) -> Result<(), String> {
    let params = PipelineParams::default();
    let prep = |mesh: &FaceMesh| {
        if deep && let Ok(rig) = facebem::prep_rig(mesh, &params) {
            let _ = facebem::describe::describe(Path::new("x"), mesh, &rig, None);
        }
    };
    match ctx.target.as_str() {
        "obj" => {
            if let Ok(mesh) = FaceMesh::from_obj_bytes(data, &Default::default()) {
                prep(&mesh);
            }
        }
        "gltf" => {
            let path = ctx.work.join(format!("case.{}", ext("gltf", data)));
            std::fs::write(&path, data).map_err(|e| e.to_string())?;
            if let Ok(mesh) = face_prep::load_face(&path) {
                prep(&mesh);
            }
        }
        "rig" => {
            if let Ok(model) = cache::from_bytes(Path::new("case.rig"), data) {
                let sliders = facebem::presets::find("happy")
                    .map(|p| p.sliders_for(model.muscle_ids()))
                    .unwrap_or_default();
                if let Ok(posed) = model.pose(&sliders)
                    && posed.iter().any(|p| !p.is_finite())
                {
                    return Err("a validated rig posed to non-finite coordinates".into());
                }
                let _ = model.obj_text(&sliders);
                let _ = facebem::export::export_gltf(&model.basis, &Default::default());
            }
        }
        _ => {
            let text = String::from_utf8_lossy(data);
            if let Ok(list) = muscle_file::read_str(&text, ctx.element_count)
                && let Some(m) = &ctx.model
            {
                let _ = m.rig.clone().with_muscles(list);
            }
        }
    }
    Ok(())
}

fn hash(data: &[u8]) -> String {
    blake3::hash(data).to_hex()[..16].to_owned()
}

// ---------------------------------------------------------------- worker and supervisor

fn worker(o: &Opts) -> Result<(), String> {
    let clock = Clock::start(true);
    let budget_s = o.minutes * 60.0;
    let seeds_dir = o.out.join("seeds");
    let mut seeds: Vec<Vec<u8>> = Vec::new();
    for e in std::fs::read_dir(&seeds_dir).map_err(|e| e.to_string())? {
        let p = e.map_err(|e| e.to_string())?.path();
        if p.extension().is_some_and(|x| x != "bin") {
            seeds.push(std::fs::read(&p).map_err(|e| e.to_string())?);
        }
    }
    seeds.sort();
    let model = match std::fs::read(o.out.join("model.rig")) {
        Ok(b) => Some(cache::from_bytes(Path::new("model.rig"), &b).map_err(|e| e.to_string())?),
        Err(_) => None,
    };
    let ctx = std::sync::Arc::new(Ctx {
        target: o.target.clone(),
        work: o.out.join("work"),
        element_count: model.as_ref().map_or(0, |m| m.rig.shell.element_count()),
        model,
    });
    let message = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
    let m2 = message.clone();
    std::panic::set_hook(Box::new(move |info| {
        if let Ok(mut m) = m2.lock() {
            *m = info.to_string();
        }
    }));
    let mut r = Rng(o.seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let (mut cases, mut panics, mut max_ms, mut max_peak) = (0u64, 0u64, 0f64, 0usize);
    let mut max_wall_ms = 0f64;
    let stats = |cases, panics, max_ms: f64, max_wall_ms: f64, max_peak: usize| {
        println!(
            "STATS {cases} {panics} {max_ms:.1} {} {max_wall_ms:.1}",
            max_peak >> 20
        );
    };
    while clock.cpu() < budget_s {
        let seed = &seeds[r.below(seeds.len())];
        let data = match o.target.as_str() {
            "obj" | "muscles" => mutate_text(&mut r, &String::from_utf8_lossy(seed)),
            "gltf" => mutate_gltf(&mut r, seed),
            _ => mutate_rig(&mut r, seed, ctx.model.as_ref().ok_or("no model")?),
        };
        let e = ext(&o.target, &data);
        std::fs::write(o.out.join(format!("inflight.{e}")), &data).map_err(|e| e.to_string())?;
        let deep = o.target != "obj" && o.target != "gltf" || r.chance(4);
        let base = LIVE.load(Relaxed);
        PEAK.store(base, Relaxed);
        LIMIT.store(base + (o.case_mb << 20), Relaxed);
        let (tx, rx) = std::sync::mpsc::channel();
        let (c2, d2) = (ctx.clone(), data.clone());
        let case_clock = Clock::start(true);
        std::thread::Builder::new()
            .stack_size(8 << 20)
            .spawn(move || {
                let res = std::panic::catch_unwind(|| run_case(&c2, &d2, deep));
                let _ = tx.send(res);
            })
            .map_err(|e| e.to_string())?;
        // Poll: slow is over `case_seconds` of CPU, or over `hang_seconds` of wall-clock time.
        let outcome = loop {
            match rx.recv_timeout(Duration::from_millis(50)) {
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                    if case_clock.cpu() > o.case_seconds || case_clock.wall() > o.hang_seconds {
                        break None;
                    }
                }
                Ok(r) => break Some(r),
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break None,
            }
        };
        let ms = case_clock.cpu() * 1e3;
        let wall_ms = case_clock.wall() * 1e3;
        LIMIT.store(usize::MAX, Relaxed);
        max_peak = max_peak.max(PEAK.load(Relaxed).saturating_sub(base));
        max_ms = max_ms.max(ms);
        max_wall_ms = max_wall_ms.max(wall_ms);
        cases += 1;
        let save = |kind: &str, note: &str| {
            let name = format!("{kind}-{}.{e}", hash(&data));
            let _ = std::fs::write(o.out.join(&name), &data);
            let _ = std::fs::write(o.out.join(format!("{name}.txt")), note);
        };
        match outcome {
            Some(Ok(Ok(()))) => {}
            Some(Ok(Err(oracle))) => {
                panics += 1;
                save("wrong", &oracle);
            }
            Some(Err(_)) => {
                panics += 1;
                save(
                    "panic",
                    &message.lock().map(|m| m.clone()).unwrap_or_default(),
                );
            }
            None => {
                save(
                    "slow",
                    &format!(
                        "over {} s of CPU or {} s of wall-clock time ({:.1} s CPU, {:.1} s wall)",
                        o.case_seconds,
                        o.hang_seconds,
                        ms / 1e3,
                        wall_ms / 1e3
                    ),
                );
                stats(cases, panics, max_ms, max_wall_ms, max_peak);
                std::process::exit(3);
            }
        }
        if cases % 500 == 0 {
            stats(cases, panics, max_ms, max_wall_ms, max_peak);
        }
    }
    stats(cases, panics, max_ms, max_wall_ms, max_peak);
    Ok(())
}

fn prepare_seeds(o: &Opts) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let seeds = o.out.join("seeds");
    std::fs::create_dir_all(&seeds).map_err(|e| err(&e))?;
    std::fs::create_dir_all(o.out.join("work")).map_err(|e| err(&e))?;
    let face_text = std::fs::read_to_string(face_path()).map_err(|e| err(&e))?;
    let face = FaceMesh::from_obj_str(&face_text).map_err(|e| err(&e))?;
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_inputs");
    let kinds: &[&str] = match o.target.as_str() {
        "obj" => &["obj"],
        "gltf" => &["gltf", "glb"],
        "muscles" => &["muscles"],
        _ => &[],
    };
    for e in std::fs::read_dir(&corpus).map_err(|e| err(&e))?.flatten() {
        let p = e.path();
        if p.extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| kinds.contains(&x))
        {
            let name = p.file_name().unwrap_or_default();
            std::fs::copy(&p, seeds.join(name)).map_err(|e| err(&e))?;
        }
    }
    match o.target.as_str() {
        "obj" => std::fs::write(seeds.join("face.obj"), &face_text).map_err(|e| err(&e))?,
        "gltf" => {
            let (glb, data, external, bin) = gltf_seeds(&face);
            std::fs::write(seeds.join("face.glb"), glb).map_err(|e| err(&e))?;
            std::fs::write(seeds.join("face_data.gltf"), data).map_err(|e| err(&e))?;
            std::fs::write(seeds.join("face_external.gltf"), external).map_err(|e| err(&e))?;
            let work = o.out.join("work");
            std::fs::write(work.join("face.bin"), &bin).map_err(|e| err(&e))?;
            let fifo = work.join("fifo.bin");
            if !fifo.exists() {
                let _ = std::process::Command::new("mkfifo").arg(&fifo).status();
            }
            // A file one level up that must never be read.
            std::fs::write(o.out.join("face.bin"), &bin).map_err(|e| err(&e))?;
        }
        _ => {
            let model =
                facebem::build_face_model(&face, &PipelineParams::default(), &Control::new())
                    .map_err(|e| err(&e))?;
            let mut model = model;
            model.obj_source = Some(face_text);
            let bytes = cache::to_bytes(&model).map_err(|e| err(&e))?;
            std::fs::write(o.out.join("model.rig"), &bytes).map_err(|e| err(&e))?;
            if o.target == "rig" {
                std::fs::write(seeds.join("face.rig"), &bytes).map_err(|e| err(&e))?;
            } else {
                let text = muscle_file::to_string(&model.rig.muscles).map_err(|e| err(&e))?;
                std::fs::write(seeds.join("face.muscles"), text).map_err(|e| err(&e))?;
            }
        }
    }
    Ok(())
}

fn supervisor(o: &Opts) -> Result<(), String> {
    prepare_seeds(o)?;
    // The workers' CPU time (this process's waited-for children), wall-clock without /proc.
    let clock = Clock::start(false);
    let budget_s = o.minutes * 60.0;
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let (mut cases, mut panics, mut max_ms, mut max_peak) = (0u64, 0u64, 0f64, 0u64);
    let mut max_wall_ms = 0f64;
    let (mut crashes, mut slow, mut restarts) = (0u64, 0u64, 0u64);
    while clock.cpu() < budget_s {
        let left = (budget_s - clock.cpu()) / 60.0;
        let mut cmd = std::process::Command::new(&exe);
        if std::env::var_os("RAYON_NUM_THREADS").is_none() {
            cmd.env("RAYON_NUM_THREADS", "1");
        }
        let out = cmd
            .args(["--worker", "--target", &o.target, "--out"])
            .arg(&o.out)
            .args([
                "--minutes",
                &left.to_string(),
                "--seed",
                &(o.seed + restarts).to_string(),
            ])
            .args([
                "--case-seconds",
                &o.case_seconds.to_string(),
                "--hang-seconds",
                &o.hang_seconds.to_string(),
                "--case-mb",
                &o.case_mb.to_string(),
            ])
            .stderr(std::process::Stdio::inherit())
            .output()
            .map_err(|e| e.to_string())?;
        restarts += 1;
        let stdout = String::from_utf8_lossy(&out.stdout);
        if let Some(last) = stdout.lines().rev().find(|l| l.starts_with("STATS ")) {
            let f: Vec<f64> = last
                .split(' ')
                .skip(1)
                .filter_map(|x| x.parse().ok())
                .collect();
            if f.len() == 5 {
                cases += f[0] as u64;
                panics += f[1] as u64;
                max_ms = max_ms.max(f[2]);
                max_peak = max_peak.max(f[3] as u64);
                max_wall_ms = max_wall_ms.max(f[4]);
            }
        }
        match out.status.code() {
            Some(0) => {}
            Some(3) => slow += 1,
            _ => {
                crashes += 1;
                for e in ["obj", "gltf", "glb", "rig", "muscles"] {
                    let inflight = o.out.join(format!("inflight.{e}"));
                    if inflight.exists() {
                        let to = o.out.join(format!("crash-{crashes}.{e}"));
                        let _ = std::fs::rename(&inflight, &to);
                        eprintln!(
                            "worker died ({}); input saved as {}",
                            out.status,
                            to.display()
                        );
                    }
                }
            }
        }
    }
    let summary = format!(
        "target {}: {:.1} CPU min ({:.1} min wall), {cases} cases ({:.0}/CPU s), {panics} panics \
         or wrong results, {crashes} aborts, {slow} cases over {} s CPU / {} s wall, slowest case \
         {max_ms:.0} ms CPU ({max_wall_ms:.0} ms wall), largest per-case heap peak {max_peak} MiB \
         (limit {} MiB), {restarts} worker runs; findings in {}\n",
        o.target,
        clock.cpu() / 60.0,
        clock.wall() / 60.0,
        cases as f64 / clock.cpu().max(1e-9),
        o.case_seconds,
        o.hang_seconds,
        o.case_mb,
        o.out.display()
    );
    print!("{summary}");
    let _ = std::fs::write(o.out.join("summary.txt"), &summary);
    if panics + crashes + slow > 0 {
        return Err("findings: see above".into());
    }
    Ok(())
}

fn main() {
    let result = parse_opts().and_then(|o| if o.worker { worker(&o) } else { supervisor(&o) });
    if let Err(e) = result {
        eprintln!("fuzz: {e}");
        std::process::exit(1);
    }
}

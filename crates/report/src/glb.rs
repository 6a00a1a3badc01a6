//! glTF 2.0 binary export (`run.glb`), written by hand: one node per body, each an
//! icosphere scaled to the body's radius and coloured by arc length, animated by one
//! LINEAR translation sampler per node over the frames' times; then one grey wireframe node
//! (LINES) per obstacle, animated the same way when it moves. glTF is in metres with +Y up,
//! so a point (x, y, z) cm becomes (x, z, −y) / 100 m.

use std::collections::HashMap;

use glam::DQuat;
use serde::{Serialize, Serializer};
use serde_json::{Value, json};

use crate::centreline::Centreline;
use crate::colour::sequential;
use crate::obstacles::{ObstacleTrack, Pose};

/// glTF primitive mode of line segments (vertex pairs).
const LINES: u32 = 1;
/// glTF component type of f32.
const FLOAT: u32 = 5126;
/// glTF component type of u16.
const UNSIGNED_SHORT: u32 = 5123;
/// bufferView targets.
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// Chunk types and the file magic.
const MAGIC: u32 = 0x4654_6C67;
const JSON_CHUNK: u32 = 0x4E4F_534A;
const BIN_CHUNK: u32 = 0x004E_4942;

/// A unit icosphere: vertices (also the normals) and triangles, counter-clockwise outside.
pub fn icosphere(subdivisions: usize) -> (Vec<[f32; 3]>, Vec<[u16; 3]>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut vertices: Vec<[f32; 3]> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .map(normalise)
    .to_vec();
    let mut triangles: Vec<[u16; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoints: HashMap<(u16, u16), u16> = HashMap::new();
        let mut midpoint = |a: u16, b: u16, vertices: &mut Vec<[f32; 3]>| {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (vertices[usize::from(a)], vertices[usize::from(b)]);
                vertices.push(normalise([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                (vertices.len() - 1) as u16
            })
        };
        triangles = triangles
            .iter()
            .flat_map(|&[a, b, c]| {
                let ab = midpoint(a, b, &mut vertices);
                let bc = midpoint(b, c, &mut vertices);
                let ca = midpoint(c, a, &mut vertices);
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    (vertices, triangles)
}

fn normalise(v: [f32; 3]) -> [f32; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

/// A point in cm, z up → glTF metres, y up.
fn to_gltf(p: [f64; 3]) -> [f32; 3] {
    [(p[0] / 100.0) as f32, (p[2] / 100.0) as f32, (-p[1] / 100.0) as f32]
}

/// The binary buffer being assembled, with its buffer views: `bytes`, then `trailing` bytes
/// of a last view whose data [`encode`] writes straight into the file's bytes (the
/// translation tracks: frames × bodies × 12 bytes, the bulk of the file, not copied twice).
#[derive(Default)]
struct Buffer {
    bytes: Vec<u8>,
    trailing: usize,
    views: Vec<Value>,
}

impl Buffer {
    /// Appends `data` as a new buffer view (4-byte aligned) and returns its index.
    fn view(&mut self, data: &[u8], target: Option<u32>) -> usize {
        pad(&mut self.bytes, 0);
        let mut view =
            json!({ "buffer": 0, "byteOffset": self.bytes.len(), "byteLength": data.len() });
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        self.bytes.extend_from_slice(data);
        self.views.push(view);
        self.views.len() - 1
    }

    /// Adds the last view, of `length` bytes (a multiple of 4) written after `bytes`, and
    /// returns its index.
    fn trailing_view(&mut self, length: usize) -> usize {
        pad(&mut self.bytes, 0);
        self.trailing = length;
        self.views
            .push(json!({ "buffer": 0, "byteOffset": self.bytes.len(), "byteLength": length }));
        self.views.len() - 1
    }

    /// The buffer's length in bytes.
    fn len(&self) -> usize {
        self.bytes.len() + self.trailing
    }
}

/// Appends `with` until the length is a multiple of 4 (glTF's alignment).
fn pad(bytes: &mut Vec<u8>, with: u8) {
    while !bytes.len().is_multiple_of(4) {
        bytes.push(with);
    }
}

fn floats(values: impl IntoIterator<Item = f32>) -> Vec<u8> {
    values.into_iter().flat_map(f32::to_le_bytes).collect()
}

/// The glTF document, written with its keys in the order `serde_json`'s own maps sort them.
/// The per-body arrays are [`Elements`]: a 10 000-body run would otherwise hold ≈ 60 000
/// `Value`s at once (measured: 150 MB of the peak of `hagfish render`).
#[derive(Serialize)]
struct Document<'a> {
    accessors: Elements<'a>,
    animations: [Animation<'a>; 1],
    asset: Value,
    #[serde(rename = "bufferViews")]
    buffer_views: &'a [Value],
    buffers: Value,
    materials: Elements<'a>,
    meshes: Elements<'a>,
    nodes: Elements<'a>,
    scene: usize,
    scenes: Value,
}

/// The document's one animation: a translation channel and sampler per body.
#[derive(Serialize)]
struct Animation<'a> {
    channels: Elements<'a>,
    name: &'static str,
    samplers: Elements<'a>,
}

/// A JSON array of the `first` values, then `each(0) … each(count − 1)`, each made as it is
/// written and dropped after, then the `last` values.
struct Elements<'a> {
    first: &'a [Value],
    count: usize,
    each: &'a dyn Fn(usize) -> Value,
    last: &'a [Value],
}

impl Serialize for Elements<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let each = (0..self.count).map(self.each);
        serializer
            .collect_seq(self.first.iter().cloned().chain(each).chain(self.last.iter().cloned()))
    }
}

/// The accessors, meshes, nodes and animation entries of the obstacles, numbered after the
/// bodies' (their buffer views appended to `buffer`).
struct ObstacleParts {
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    samplers: Vec<Value>,
    channels: Vec<Value>,
}

impl ObstacleParts {
    /// The parts of `obstacles`; `accessors` and `bodies` are the counts before theirs (the
    /// bodies' meshes, nodes, samplers and the one obstacle material after theirs).
    fn new(
        obstacles: &[ObstacleTrack],
        buffer: &mut Buffer,
        accessors: usize,
        bodies: usize,
    ) -> Self {
        let mut parts = ObstacleParts {
            accessors: Vec::new(),
            meshes: Vec::new(),
            nodes: Vec::new(),
            samplers: Vec::new(),
            channels: Vec::new(),
        };
        for (k, obstacle) in obstacles.iter().enumerate() {
            let segments = obstacle.lines.iter().flat_map(|line| line.windows(2).flatten());
            let points: Vec<[f32; 3]> = segments.map(|&p| to_gltf(p)).collect();
            let (low, high) = points.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(l, h), p| {
                ([0, 1, 2].map(|a| l[a].min(p[a])), [0, 1, 2].map(|a| h[a].max(p[a])))
            });
            let view = buffer.view(&floats(points.iter().flatten().copied()), Some(ARRAY_BUFFER));
            let positions = accessors + parts.accessors.len();
            parts.accessors.push(json!({
                "bufferView": view, "componentType": FLOAT, "count": points.len(),
                "type": "VEC3", "min": low, "max": high
            }));
            parts.meshes.push(json!({ "primitives": [{
                "attributes": { "POSITION": positions }, "mode": LINES, "material": bodies
            }] }));
            let node = bodies + k;
            let translation = |pose: &Pose| to_gltf(pose.translation.to_array());
            let start = obstacle.poses.first().map_or([0.0; 3], translation);
            let rotation = obstacle.poses.first().map_or([0.0, 0.0, 0.0, 1.0], gltf_rotation);
            parts.nodes.push(json!({
                "name": format!("obstacle {k}"), "mesh": node, "translation": start,
                "rotation": rotation
            }));
            if obstacle.poses.is_empty() {
                continue;
            }
            let translations = obstacle.poses.iter().flat_map(translation);
            parts.animate(buffer, (accessors, bodies), node, ("translation", "VEC3"), translations);
            if obstacle.poses.iter().any(|pose| pose.rotation != DQuat::IDENTITY) {
                let rotations = obstacle.poses.iter().flat_map(gltf_rotation);
                parts.animate(buffer, (accessors, bodies), node, ("rotation", "VEC4"), rotations);
            }
        }
        parts
    }

    /// Animates `path` (`translation` or `rotation`, values of glTF type `kind`, one per
    /// frame in `values`) of `node`, linearly between frames (spherically for a rotation).
    fn animate(
        &mut self,
        buffer: &mut Buffer,
        (accessors, bodies): (usize, usize),
        node: usize,
        (path, kind): (&str, &str),
        values: impl Iterator<Item = f32>,
    ) {
        let values: Vec<f32> = values.collect();
        let count = values.len() / if kind == "VEC4" { 4 } else { 3 };
        let view = buffer.view(&floats(values), None);
        let output = accessors + self.accessors.len();
        self.accessors.push(json!({
            "bufferView": view, "componentType": FLOAT, "count": count, "type": kind
        }));
        let sampler = bodies + self.samplers.len();
        self.samplers.push(json!({ "input": 3, "output": output, "interpolation": "LINEAR" }));
        self.channels.push(json!({ "sampler": sampler, "target": { "node": node, "path": path } }));
    }
}

/// A pose's rotation as a glTF quaternion (x, y, z, w) in [`to_gltf`]'s axes (x, z, −y): the
/// same turn about the axis carried over.
fn gltf_rotation(pose: &Pose) -> [f32; 4] {
    let q = pose.rotation;
    [q.x as f32, q.z as f32, -q.y as f32, q.w as f32]
}

/// The `.glb` bytes of the animated run: `radii` per body (cm), and the `obstacles` (their
/// offsets, when they move, one per frame).
pub fn encode(centreline: &Centreline, radii: &[f64], obstacles: &[ObstacleTrack]) -> Vec<u8> {
    let (vertices, triangles) = icosphere(1);
    let (bodies, frames) = (centreline.bodies, centreline.frames());
    let mut buffer = Buffer::default();
    let positions = buffer.view(&floats(vertices.iter().flatten().copied()), Some(ARRAY_BUFFER));
    let normals = buffer.view(&floats(vertices.iter().flatten().copied()), Some(ARRAY_BUFFER));
    let index_bytes: Vec<u8> = triangles.iter().flatten().flat_map(|i| i.to_le_bytes()).collect();
    let indices = buffer.view(&index_bytes, Some(ELEMENT_ARRAY_BUFFER));
    let times = buffer.view(&floats(centreline.times.iter().map(|t| *t as f32)), None);
    let obstacle_parts = ObstacleParts::new(obstacles, &mut buffer, 4 + bodies, bodies);
    let tracks =
        (0..bodies).flat_map(|b| (0..frames).flat_map(move |f| to_gltf(centreline.frame(f)[b])));
    let translations = buffer.trailing_view(12 * frames * bodies);

    let (t0, t1) = (centreline.times[0] as f32, centreline.times[frames - 1] as f32);
    let fixed_accessors = vec![
        json!({
            "bufferView": positions, "componentType": FLOAT, "count": vertices.len(),
            "type": "VEC3", "min": [-1.0, -1.0, -1.0], "max": [1.0, 1.0, 1.0]
        }),
        json!({
            "bufferView": normals, "componentType": FLOAT, "count": vertices.len(),
            "type": "VEC3"
        }),
        json!({
            "bufferView": indices, "componentType": UNSIGNED_SHORT,
            "count": 3 * triangles.len(), "type": "SCALAR"
        }),
        json!({
            "bufferView": times, "componentType": FLOAT, "count": frames, "type": "SCALAR",
            "min": [t0], "max": [t1]
        }),
    ];
    let first_track = fixed_accessors.len();
    let track = |b: usize| {
        json!({
            "bufferView": translations, "byteOffset": 12 * frames * b,
            "componentType": FLOAT, "count": frames, "type": "VEC3"
        })
    };
    let material = |b: usize| {
        let c = sequential(b as f64 / (bodies - 1).max(1) as f64);
        let mut factor = [c[0], c[1], c[2]].map(|v| (f64::from(v) / 255.0).powf(2.2)).to_vec();
        factor.push(1.0);
        json!({ "pbrMetallicRoughness": {
            "baseColorFactor": factor, "metallicFactor": 0.0, "roughnessFactor": 0.6
        } })
    };
    let mesh = |b: usize| {
        json!({ "primitives": [{
            "attributes": { "POSITION": 0, "NORMAL": 1 }, "indices": 2, "material": b
        }] })
    };
    let node = |b: usize| {
        let r = (radii[b] / 100.0) as f32;
        json!({ "name": format!("body {b}"), "mesh": b, "scale": [r, r, r],
                "translation": to_gltf(centreline.frame(0)[b]) })
    };
    let sampler =
        |b: usize| json!({ "input": 3, "output": first_track + b, "interpolation": "LINEAR" });
    let channel =
        |b: usize| json!({ "sampler": b, "target": { "node": b, "path": "translation" } });
    let per_body = |each, last| Elements { first: &[], count: bodies, each, last };
    let grey = [json!({ "pbrMetallicRoughness": {
        "baseColorFactor": [0.4, 0.4, 0.4, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0
    } })];
    let parts = &obstacle_parts;
    let scene_nodes: Vec<usize> = (0..bodies + parts.nodes.len()).collect();
    let document = Document {
        accessors: Elements {
            first: &fixed_accessors,
            count: bodies,
            each: &track,
            last: &parts.accessors,
        },
        animations: [Animation {
            channels: per_body(&channel, &parts.channels),
            name: "run",
            samplers: per_body(&sampler, &parts.samplers),
        }],
        asset: json!({ "version": "2.0", "generator": "hagfish-report" }),
        buffer_views: &buffer.views,
        buffers: json!([{ "byteLength": buffer.len() }]),
        materials: per_body(&material, if obstacles.is_empty() { &[] } else { &grey }),
        meshes: per_body(&mesh, &parts.meshes),
        nodes: per_body(&node, &parts.nodes),
        scene: 0,
        scenes: json!([{ "name": "hagfish", "nodes": scene_nodes }]),
    };
    let mut json_bytes =
        serde_json::to_vec(&document).expect("JSON values and string keys always serialize");
    pad(&mut json_bytes, b' ');
    let total = 12 + 8 + json_bytes.len() + 8 + buffer.len();
    let mut glb = Vec::with_capacity(total);
    for word in [MAGIC, 2, total as u32, json_bytes.len() as u32, JSON_CHUNK] {
        glb.extend_from_slice(&word.to_le_bytes());
    }
    glb.extend_from_slice(&json_bytes);
    for word in [buffer.len() as u32, BIN_CHUNK] {
        glb.extend_from_slice(&word.to_le_bytes());
    }
    glb.extend_from_slice(&buffer.bytes);
    glb.extend(tracks.flat_map(f32::to_le_bytes));
    debug_assert_eq!(glb.len(), total);
    glb
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_files::two_frames;
    use glam::DVec3;

    fn word(bytes: &[u8], at: usize) -> usize {
        u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]) as usize
    }

    fn component_size(t: u64) -> usize {
        match t {
            5126 | 5125 => 4,
            5123 | 5122 => 2,
            _ => 1,
        }
    }

    fn components(t: &str) -> usize {
        match t {
            "SCALAR" => 1,
            "VEC2" => 2,
            "VEC3" => 3,
            "VEC4" | "MAT2" => 4,
            _ => 16,
        }
    }

    /// Parses a .glb and checks its structure; returns the JSON document and BIN chunk.
    fn parse(glb: &[u8]) -> (Value, Vec<u8>) {
        assert_eq!(word(glb, 0), MAGIC as usize, "magic");
        assert_eq!(word(glb, 4), 2, "version");
        assert_eq!(word(glb, 8), glb.len(), "total length");
        let json_length = word(glb, 12);
        assert_eq!(word(glb, 16), JSON_CHUNK as usize);
        assert_eq!(json_length % 4, 0);
        let document: Value =
            serde_json::from_slice(&glb[20..20 + json_length]).expect("the JSON chunk parses");
        let bin_at = 20 + json_length;
        let bin_length = word(glb, bin_at);
        assert_eq!(word(glb, bin_at + 4), BIN_CHUNK as usize);
        assert_eq!(bin_length % 4, 0);
        assert_eq!(bin_at + 8 + bin_length, glb.len(), "chunks fill the file");
        let bin = glb[bin_at + 8..].to_vec();
        assert_eq!(document["buffers"][0]["byteLength"].as_u64(), Some(bin.len() as u64));
        let views = document["bufferViews"].as_array().expect("bufferViews");
        for view in views {
            let (offset, length) = (view["byteOffset"].as_u64(), view["byteLength"].as_u64());
            let (offset, length) =
                (offset.expect("offset") as usize, length.expect("length") as usize);
            assert!(offset + length <= bin.len(), "view {view} beyond the buffer");
            assert_eq!(offset % 4, 0);
        }
        for accessor in document["accessors"].as_array().expect("accessors") {
            let view = &views[accessor["bufferView"].as_u64().expect("view") as usize];
            let offset = accessor["byteOffset"].as_u64().unwrap_or(0) as usize;
            let count = accessor["count"].as_u64().expect("count") as usize;
            let size = component_size(accessor["componentType"].as_u64().expect("type"))
                * components(accessor["type"].as_str().expect("type"));
            let length = view["byteLength"].as_u64().expect("length") as usize;
            assert!(
                count > 0 && offset + count * size <= length,
                "accessor {accessor} beyond its view"
            );
        }
        (document, bin)
    }

    #[test]
    fn an_icosphere_has_the_expected_counts_and_unit_vertices() {
        let (v, t) = icosphere(1);
        assert_eq!((v.len(), t.len()), (42, 80));
        assert!(v.iter().all(|p| ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0).abs() < 1e-6));
        assert!(t.iter().flatten().all(|i| usize::from(*i) < v.len()));
    }

    #[test]
    fn the_glb_parses_back_with_one_animated_node_per_body() {
        let centreline = two_frames();
        let glb = encode(&centreline, &[1.0, 0.5, 0.25], &[]);
        let (document, bin) = parse(&glb);
        assert_eq!(document["asset"]["version"], "2.0");
        assert_eq!(document["nodes"].as_array().map(Vec::len), Some(3));
        assert_eq!(document["nodes"][1]["scale"][0].as_f64(), Some(f64::from(0.005f32)));
        let animation = &document["animations"][0];
        assert_eq!(animation["channels"].as_array().map(Vec::len), Some(3));
        let accessors = document["accessors"].as_array().expect("accessors");
        let times = &accessors[animation["samplers"][0]["input"].as_u64().expect("input") as usize];
        assert_eq!(times["count"].as_u64(), Some(2));
        assert_eq!(times["max"][0].as_f64(), Some(0.5));
        // The last body's track at frame 1: (2, 1.5, −0.25) cm → (0.02, −0.0025, −0.015) m.
        let track =
            &accessors[animation["samplers"][2]["output"].as_u64().expect("output") as usize];
        assert_eq!(track["count"].as_u64(), Some(2));
        let view = &document["bufferViews"][track["bufferView"].as_u64().expect("view") as usize];
        let at = view["byteOffset"].as_u64().expect("o") as usize
            + track["byteOffset"].as_u64().expect("o") as usize
            + 12;
        let value: Vec<f32> = (0..3)
            .map(|k| {
                f32::from_le_bytes([
                    bin[at + 4 * k],
                    bin[at + 4 * k + 1],
                    bin[at + 4 * k + 2],
                    bin[at + 4 * k + 3],
                ])
            })
            .collect();
        assert_eq!(value, vec![0.02, -0.0025, -0.015]);
    }

    #[test]
    fn obstacles_are_grey_line_nodes_after_the_bodies_and_a_moving_one_is_animated() {
        let centreline = two_frames();
        let square = vec![vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]];
        let still = ObstacleTrack { lines: square.clone(), poses: Vec::new() };
        let at = |z: f64| Pose { rotation: DQuat::IDENTITY, translation: DVec3::new(0.0, 0.0, z) };
        let moving = ObstacleTrack { lines: square.clone(), poses: vec![at(0.0), at(10.0)] };
        let turned = Pose { rotation: DQuat::from_rotation_z(0.5), translation: DVec3::ZERO };
        let turning = ObstacleTrack { lines: square, poses: vec![at(0.0), turned] };
        let glb = encode(&centreline, &[1.0, 0.5, 0.25], &[still, moving, turning]);
        let (document, _) = parse(&glb);
        assert_eq!(document["nodes"].as_array().map(Vec::len), Some(6));
        assert_eq!(document["scenes"][0]["nodes"].as_array().map(Vec::len), Some(6));
        let primitive = &document["meshes"][3]["primitives"][0];
        assert_eq!(primitive["mode"].as_u64(), Some(u64::from(LINES)));
        assert_eq!(primitive["material"].as_u64(), Some(3), "the grey material after the bodies'");
        let positions = primitive["attributes"]["POSITION"].as_u64().expect("positions") as usize;
        assert_eq!(document["accessors"][positions]["count"].as_u64(), Some(4), "two segments");
        let channels = document["animations"][0]["channels"].as_array().expect("channels");
        assert_eq!(channels.len(), 6, "three bodies, the moving obstacle, the turning one twice");
        assert_eq!(channels[3]["target"]["node"].as_u64(), Some(4));
        assert_eq!(document["nodes"][4]["translation"][2].as_f64(), Some(0.0));
        let targets = [4, 5].map(|c| channels[c]["target"].clone());
        assert_eq!(targets[0]["path"], "translation");
        assert_eq!(
            (targets[1]["node"].as_u64(), &targets[1]["path"]),
            (Some(5), &json!("rotation"))
        );
        let sampler = channels[5]["sampler"].as_u64().expect("sampler") as usize;
        let output = document["animations"][0]["samplers"][sampler]["output"].as_u64();
        let accessor = &document["accessors"][output.expect("output") as usize];
        assert_eq!(
            (accessor["type"].as_str(), accessor["count"].as_u64()),
            (Some("VEC4"), Some(2))
        );
        // A turn about the model's z (up) is a turn about glTF's y (up).
        let q = gltf_rotation(&turned);
        assert!(q[0] == 0.0 && q[1] > 0.0 && q[2] == 0.0 && q[3] > 0.0, "{q:?}");
    }
}

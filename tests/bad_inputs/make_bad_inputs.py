import json, struct, base64, copy
def tri_doc():
    pos = struct.pack('<9f', 0,0,0, 1,0,0, 0,1,0)
    idx = struct.pack('<3I', 0,1,2)
    buf = pos+idx
    return {
      "asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
      "nodes":[{"mesh":0}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
      "buffers":[{"byteLength":len(buf),"uri":"data:application/octet-stream;base64,"+base64.b64encode(buf).decode()}],
      "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                   {"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}]}
out={}
d=tri_doc(); d["nodes"]=[{"children":[0]},{"mesh":0}]; d["scenes"]=[{"nodes":[0,1]}]; out["gltf_node_self_child.gltf"]=d
d=tri_doc(); d["accessors"][0]["sparse"]={"count":2**62,"indices":{"bufferView":1,"componentType":5125},"values":{"bufferView":0}}; out["gltf_sparse_count_2p62_small_accessor.gltf"]=d
d=tri_doc(); d["nodes"]=[{"children":[1]},{"children":[0]},{"mesh":0}]; d["scenes"]=[{"nodes":[0]}]; out["gltf_node_cycle.gltf"]=d
d=tri_doc(); n=2000; d["nodes"]=[{"children":[i+1]} for i in range(n)]+[{"mesh":0}]; out["gltf_node_nested_2000.gltf"]=d
d=tri_doc(); d["meshes"][0]["primitives"][0]["attributes"]["POSITION"]=5; out["gltf_position_accessor_out_of_range.gltf"]=d
d=tri_doc(); d["accessors"]=[]; out["gltf_no_accessors.gltf"]=d
d=tri_doc(); d["accessors"][1]["componentType"]=5126; out["gltf_float_indices.gltf"]=d
d=tri_doc(); d["bufferViews"][0]["byteStride"]=4; out["gltf_stride_smaller_than_element.gltf"]=d
d=tri_doc(); d["buffers"][0]["uri"]="%FF"; out["gltf_uri_percent_ff.gltf"]=d
d=tri_doc(); d["accessors"][0]["sparse"]={"count":2**62,"indices":{"bufferView":1,"componentType":5125},"values":{"bufferView":0}}; d["accessors"][0]["count"]=2**62; out["gltf_sparse_count_2p62.gltf"]=d
d=tri_doc(); a=d["accessors"][0]; del a["bufferView"]; a["count"]=2**40; a["sparse"]={"count":1,"indices":{"bufferView":1,"componentType":5125},"values":{"bufferView":0}}; out["gltf_sparse_no_view_count_2p40.gltf"]=d
d=tri_doc(); d["buffers"][0]["uri"]="file:///dev/zero"; d["buffers"][0]["byteLength"]=2**40; out["gltf_uri_file_dev_zero.gltf"]=d
d=tri_doc(); d["buffers"][0]["uri"]="file:///dev/zero"; out["gltf_uri_file_dev_zero_small.gltf"]=d
d=tri_doc(); d["buffers"][0]["uri"]="/etc/passwd"; out["gltf_uri_absolute_etc_passwd.gltf"]=d
d=tri_doc(); d["buffers"][0]["uri"]="../../../../../../etc/passwd"; out["gltf_uri_parent_folder.gltf"]=d
d=tri_doc(); d["accessors"][1]["bufferView"]=9; out["gltf_indices_view_out_of_range.gltf"]=d
d=tri_doc(); d["accessors"][0]["count"]=4; out["gltf_position_past_its_view.gltf"]=d
d=tri_doc(); d["bufferViews"][0]["byteLength"]=4000; out["gltf_view_past_its_buffer.gltf"]=d
d=tri_doc(); d["meshes"][0]["primitives"][0]["mode"]=1; out["gltf_lines_mode.gltf"]=d
d=tri_doc(); d["scene"]=7; out["gltf_scene_out_of_range.gltf"]=d
d=tri_doc(); d["nodes"][0]["children"]=[99]; d["nodes"].append({"mesh":0}); d["nodes"][0].pop("mesh"); out["gltf_child_out_of_range.gltf"]=d
for k,v in out.items():
    open(k,'w').write(json.dumps(v))
open('gltf_not_json.gltf','w').write('{"asset": {"version": "2.0"}, "meshes": [')
# GLBs
js=json.dumps(tri_doc()).encode(); js+=b' '*((4-len(js)%4)%4)
def glb(chunks, version=2, total=None):
    body=b''.join(struct.pack('<II',len(c) if l is None else l,t)+c for (t,c,l) in chunks)
    tot=12+len(body) if total is None else total
    return b'glTF'+struct.pack('<II',version,tot)+body
open('glb_version_1.glb','wb').write(glb([(0x4E4F534A,js,None)],version=1))
open('glb_chunk_longer_than_file.glb','wb').write(glb([(0x4E4F534A,js,0x7fffffff)]))
open('glb_first_chunk_binary.glb','wb').write(glb([(0x004E4942,js,None)]))
open('glb_truncated_header.glb','wb').write(b'glTF\x02\x00')
d=tri_doc(); d["buffers"][0].pop("uri"); js2=json.dumps(d).encode(); js2+=b' '*((4-len(js2)%4)%4)
open('glb_no_binary_chunk.glb','wb').write(glb([(0x4E4F534A,js2,None)]))
# OBJ
open('obj_coordinate_1e300.obj','w').write("v 0 0 0\nv 1e300 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
open('obj_coordinate_nan.obj','w').write("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")
s="v 0 0 0\nv 1 0 0\nv 0 1 0\n"+"f 1 2 3\n"*2000
open('obj_2000_duplicate_triangles.obj','w').write(s)
open('obj_closed_tetrahedron.obj','w').write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
open('obj_index_out_of_range.obj','w').write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n")
s=''.join(f"v {k} 0 0\nv {k+0.5} 1 0\nv {k+1} 0 0\n" for k in range(0,60,2))+''.join(f"f {i+1} {i+3} {i+2}\n" for i in range(0,90,3))
open('obj_many_components.obj','w').write(s)
open('obj_empty.obj','w').write("# nothing\n")
# muscles
open('muscles_size_4294967295.muscles','w').write("[Name]\nFrontalis L\n[Size]\n4294967295\n[Data]\n1\n2\n")
open('muscles_300_muscles.muscles','w').write("".join(f"[Name]\nm{i}\n[Size]\n1\n[Data]\n{i}\n" for i in range(300)))
open('muscles_huge_index.muscles','w').write("[Name]\nFrontalis L\n[Size]\n1\n[Data]\n4294967295\n")
open('muscles_negative_size.muscles','w').write("[Name]\nFrontalis L\n[Size]\n-1\n[Data]\n")
open('muscles_long_garbage_line.muscles','w').write("[Name]\nFrontalis L\n[Size]\n"+"9"*5000+"\n")
# A whole head (UV sphere) cut at the neck, with holes at both eyes and the mouth: four loops,
# but the largest (the "outer" one) is the neck cut below the mouth, not the face's outline.
import math
NLAT, NLON = 24, 48
verts, faces = [], []
def vid(i, j): return i * NLON + (j % NLON)
for i in range(NLAT + 1):
    lat = -math.pi / 2 + math.pi * i / NLAT
    for j in range(NLON):
        lon = 2 * math.pi * j / NLON
        verts.append((math.cos(lat) * math.sin(lon), math.sin(lat), math.cos(lat) * math.cos(lon)))
holes = {(14, 45), (14, 3), (8, 0), (8, 47)}  # (lat band, lon cell): eye R, eye L, mouth (2 cells)
for i in range(NLAT):
    for j in range(NLON):
        if i < 4 or (i, j) in holes:  # below the neck cut, or a hole
            continue
        a, b, c, d = vid(i, j), vid(i, j + 1), vid(i + 1, j + 1), vid(i + 1, j)
        if i == NLAT - 1:
            faces.append((a, b, c))
        else:
            faces += [(a, b, c), (a, c, d)]
used = sorted({v for f in faces for v in f})
remap = {v: k + 1 for k, v in enumerate(used)}
with open('obj_head_cut_at_neck.obj', 'w') as f:
    f.write("# a whole head cut at the neck (not a front face)\n")
    for v in used:
        f.write("v %.6f %.6f %.6f\n" % verts[v])
    for t in faces:
        f.write("f %d %d %d\n" % tuple(remap[v] for v in t))
# Non-finite numbers, zero w and forward references are refused when the file is read (issue:
# hostile input, parts 4 and 6), so nothing accepted fails later in an export.
def tri_doc_with(semantic, values, fmt, kind):
    d = tri_doc()
    extra = struct.pack(fmt, *values)
    buf = base64.b64decode(d["buffers"][0]["uri"].split(",")[1]) + extra
    d["buffers"][0] = {"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}
    d["bufferViews"].append({"buffer": 0, "byteOffset": 48, "byteLength": len(extra)})
    d["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 3, "type": kind})
    d["meshes"][0]["primitives"][0]["attributes"][semantic] = 2
    return d
nan, inf = float('nan'), float('inf')
open('gltf_texcoord_nan.gltf', 'w').write(json.dumps(tri_doc_with("TEXCOORD_0", [0, 0, nan, 0, 0, 1], '<6f', "VEC2")))
open('gltf_normal_infinite.gltf', 'w').write(json.dumps(tri_doc_with("NORMAL", [0, 0, 1, 0, 0, 1, inf, 0, 1], '<9f', "VEC3")))
open('obj_texcoord_nan.obj', 'w').write("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt nan nan\nf 1/1 2/2 3/1\n")
open('obj_normal_infinite.obj', 'w').write("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn inf 0 1\nf 1//1 2//1 3//1\n")
open('obj_w_infinite.obj', 'w').write("v 0 0 0\nv 1 0 0 inf\nv 0 1 0\nf 1 2 3\n")
open('obj_w_zero.obj', 'w').write("v 0 0 0\nv 1 0 0 0\nv 0 1 0\nf 1 2 3\n")
open('obj_vertex_after_its_face.obj', 'w').write("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n")
open('muscles_duplicate_names.muscles', 'w').write("[Name]\nFrontalis L\n[Size]\n1\n[Data]\n0\n\n[Name]\nfrontalis_l\n[Size]\n1\n[Data]\n1\n")

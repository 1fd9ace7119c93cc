// tests/draco/gen_attr_meshes.cc — the attribute benchmark set of issue 25:
// meshes of different kinds and sizes with normals, texture coordinates and
// colours, for the Draco conformance suite and `make bench-draco`.
//
//   gen-attr-meshes OUTDIR [BUNNY.obj]
//
// Geometry (deterministic, no random state outside this file):
//   scan_20k   icosphere (5 subdivisions) displaced by 4 octaves of value
//              noise: a closed, irregular, scanned-like surface, 20 480 faces
//   scan_82k   the same at 6 subdivisions, other noise: 81 920 faces
//   terrain    a 121 x 121 height field (value noise): open, one border
//   cad        an extruded 24-tooth gear with a bore, fan-triangulated caps
//              (high-valence centres) and long thin side faces, sharp edges
//   holed      a torus with 40 random patches of faces removed (holes)
//   parts      60 separate components: icospheres and subdivided boxes
//   bunny      the npm bunny (a real scan), when BUNNY.obj is given
//
// Attributes come from assimp (Debian libassimp-dev), not from this file:
// each mesh is read by assimp from an in-memory OBJ of positions and faces
// with aiProcess_GenSmoothNormals (smoothing angle 80 degrees, so the CAD
// part's sharp edges keep split normals: per-corner normals, attribute
// seams in Draco); then a spherical (plane for the terrain, cylinder for
// the gear) texture mapping is set on its material and
// aiProcess_GenUVCoords computes the texture coordinates, and
// aiProcess_JoinIdenticalVertices joins the corners that agree.
// Colours are synthesised from the normal and a band of the height (8 bits).
//
// Writes OUTDIR/NAME_n.obj (positions + normals), NAME_nt.obj (+ texture
// coordinates) and NAME_c.ply (positions + colours), positions shared
// between corners (vertices are split only where normals or texture
// coordinates differ, as in a real asset).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace {

struct V3 { double x, y, z; };
struct Mesh { std::vector<V3> v; std::vector<uint32_t> f; };

// ---- value noise --------------------------------------------------------------
uint32_t hash3(int x, int y, int z, uint32_t seed)
{
    uint32_t h = seed ^ (uint32_t)x * 0x8da6b343u ^ (uint32_t)y * 0xd8163841u ^ (uint32_t)z * 0xcb1ab31fu;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    return h ^ (h >> 15);
}

double lattice(int x, int y, int z, uint32_t seed) { return (hash3(x, y, z, seed) & 0xFFFF) / 32767.5 - 1.0; }

double smooth(double t) { return t * t * (3 - 2 * t); }

double value_noise(double x, double y, double z, uint32_t seed)
{
    const int xi = (int)std::floor(x), yi = (int)std::floor(y), zi = (int)std::floor(z);
    const double fx = smooth(x - xi), fy = smooth(y - yi), fz = smooth(z - zi);
    double c[2][2];
    for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k)
            c[j][k] = lattice(xi, yi + j, zi + k, seed) * (1 - fx) + lattice(xi + 1, yi + j, zi + k, seed) * fx;
    const double a = c[0][0] * (1 - fy) + c[1][0] * fy, b = c[0][1] * (1 - fy) + c[1][1] * fy;
    return a * (1 - fz) + b * fz;
}

double fractal(double x, double y, double z, uint32_t seed)
{
    double s = 0, amp = 1, freq = 1;
    for (int o = 0; o < 4; ++o, amp *= 0.5, freq *= 2.1)
        s += amp * value_noise(x * freq, y * freq, z * freq, seed + (uint32_t)o);
    return s;
}

// ---- shapes -----------------------------------------------------------------------
void tri(Mesh &m, uint32_t a, uint32_t b, uint32_t c) { m.f.insert(m.f.end(), {a, b, c}); }

void quad(Mesh &m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) { tri(m, a, b, c); tri(m, a, c, d); }

Mesh icosphere(int subdivisions)
{
    const double t = (1 + std::sqrt(5.0)) / 2;
    Mesh m;
    m.v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    m.f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6,
           7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7,
           9, 8, 1};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end())
                return it->second;
            const V3 p = {(m.v[a].x + m.v[b].x) / 2, (m.v[a].y + m.v[b].y) / 2, (m.v[a].z + m.v[b].z) / 2};
            m.v.push_back(p);
            return mid[key] = (uint32_t)m.v.size() - 1;
        };
        std::vector<uint32_t> f;
        for (size_t i = 0; i < m.f.size(); i += 3) {
            const uint32_t a = m.f[i], b = m.f[i + 1], c = m.f[i + 2];
            const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            f.insert(f.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        m.f.swap(f);
    }
    for (V3 &p : m.v) {
        const double l = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
        p = {p.x / l, p.y / l, p.z / l};
    }
    return m;
}

Mesh scan(int subdivisions, uint32_t seed)
{
    Mesh m = icosphere(subdivisions);
    for (V3 &p : m.v) {
        const double r = 1 + 0.25 * fractal(p.x * 1.7, p.y * 1.7, p.z * 1.7, seed) +
                         0.03 * fractal(p.x * 9, p.y * 9, p.z * 9, seed + 99);
        p = {p.x * r * 1.3, p.y * r, p.z * r * 0.8};
    }
    return m;
}

Mesh terrain(int n)
{
    Mesh m;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = i * 10.0 / (n - 1), z = j * 10.0 / (n - 1);
            m.v.push_back({x, 1.5 * fractal(x * 0.35, 0.5, z * 0.35, 7), z});
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const uint32_t a = (uint32_t)(j * n + i);
            quad(m, a, a + (uint32_t)n, a + (uint32_t)n + 1, a + 1);
        }
    return m;
}

// A gear: the outline (24 teeth, 8 samples each) and a bore of 48 samples,
// extruded over 6 rings; the caps join outline and bore by a ring of quads
// and the outline to a fan centre on a hub disc. Sharp edges at the caps.
Mesh cad()
{
    const int teeth = 24, per = 8, n = teeth * per, rings = 6, bore = 48;
    Mesh m;
    auto radius = [&](int k) {
        const int s = k % per;
        return s < 3 ? 1.0 : (s < 4 || s == 7 ? 1.08 : 1.15);
    };
    for (int r = 0; r <= rings; ++r)
        for (int k = 0; k < n; ++k) {
            const double a = 2 * M_PI * k / n, y = 0.3 * r / rings;
            m.v.push_back({radius(k) * std::cos(a), y, radius(k) * std::sin(a)});
        }
    for (int r = 0; r < rings; ++r)
        for (int k = 0; k < n; ++k) {
            const uint32_t a = (uint32_t)(r * n + k), b = (uint32_t)(r * n + (k + 1) % n);
            quad(m, a, b, b + (uint32_t)n, a + (uint32_t)n);
        }
    // bore: a cylinder of 48 samples, its caps joined to the outline by fans
    const uint32_t b0 = (uint32_t)m.v.size();
    for (int r = 0; r <= 1; ++r)
        for (int k = 0; k < bore; ++k) {
            const double a = 2 * M_PI * k / bore;
            m.v.push_back({0.35 * std::cos(a), 0.3 * r, 0.35 * std::sin(a)});
        }
    for (int k = 0; k < bore; ++k) {
        const uint32_t a = b0 + (uint32_t)k, b = b0 + (uint32_t)((k + 1) % bore);
        quad(m, b, a, a + (uint32_t)bore, b + (uint32_t)bore);
    }
    for (int cap = 0; cap <= 1; ++cap) {
        const uint32_t out = (uint32_t)(cap ? rings * n : 0), in = b0 + (uint32_t)(cap ? bore : 0);
        int j = 0;
        for (int k = 0; k < n; ++k) {  // each bore sample takes n / bore outline samples
            const int jn = (k + 1) * bore / n % bore;
            const uint32_t o0 = out + (uint32_t)k, o1 = out + (uint32_t)((k + 1) % n);
            if (cap)
                tri(m, o0, o1, in + (uint32_t)j);
            else
                tri(m, o1, o0, in + (uint32_t)j);
            if (jn != j) {
                if (cap)
                    tri(m, o1, in + (uint32_t)jn, in + (uint32_t)j);
                else
                    tri(m, in + (uint32_t)jn, o1, in + (uint32_t)j);
                j = jn;
            }
        }
    }
    return m;
}

Mesh holed()
{
    const int nu = 200, nv = 100;
    Mesh full, m;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
            full.v.push_back({(1 + 0.4 * std::cos(v)) * std::cos(u), 0.4 * std::sin(v),
                              (1 + 0.4 * std::cos(v)) * std::sin(u)});
        }
    std::vector<char> drop((size_t)nu * nv, 0);
    for (uint32_t h = 0; h < 40; ++h) {
        const int ci = (int)(hash3((int)h, 1, 2, 11) % nu), cj = (int)(hash3((int)h, 3, 4, 11) % nv);
        const int rad = 2 + (int)(hash3((int)h, 5, 6, 11) % 5);
        for (int dj = -rad; dj <= rad; ++dj)
            for (int di = -rad; di <= rad; ++di)
                if (di * di + dj * dj <= rad * rad)
                    drop[(size_t)((cj + dj + nv) % nv) * nu + (size_t)((ci + di + nu) % nu)] = 1;
    }
    m.v = full.v;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            if (drop[(size_t)j * nu + (size_t)i])
                continue;
            const uint32_t a = (uint32_t)(j * nu + i), b = (uint32_t)(j * nu + (i + 1) % nu);
            const uint32_t c = (uint32_t)(((j + 1) % nv) * nu + (i + 1) % nu), d = (uint32_t)(((j + 1) % nv) * nu + i);
            quad(m, a, b, c, d);
        }
    return m;
}

void append(Mesh &m, const Mesh &p, V3 at, double scale)
{
    const uint32_t base = (uint32_t)m.v.size();
    for (const V3 &q : p.v)
        m.v.push_back({at.x + q.x * scale, at.y + q.y * scale, at.z + q.z * scale});
    for (uint32_t i : p.f)
        m.f.push_back(base + i);
}

Mesh box(int n)  // a cube, each face an n x n grid
{
    Mesh m;
    for (int face = 0; face < 6; ++face) {
        const uint32_t base = (uint32_t)m.v.size();
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const double u = 2.0 * i / n - 1, v = 2.0 * j / n - 1, s = face & 1 ? 1 : -1;
                const int axis = face / 2;
                V3 p = axis == 0 ? V3{s, u, v} : axis == 1 ? V3{v, s, u} : V3{u, v, s};
                m.v.push_back(p);
            }
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const uint32_t a = base + (uint32_t)(j * (n + 1) + i);
                if (face & 1)
                    quad(m, a, a + 1, a + (uint32_t)n + 2, a + (uint32_t)n + 1);
                else
                    quad(m, a, a + (uint32_t)n + 1, a + (uint32_t)n + 2, a + 1);
            }
    }
    return m;
}

Mesh parts()
{
    Mesh m;
    const Mesh ball = icosphere(2), cube = box(7);
    for (uint32_t k = 0; k < 60; ++k) {
        const V3 at = {(hash3((int)k, 0, 0, 5) % 1000) / 100.0, (hash3((int)k, 1, 0, 5) % 1000) / 300.0,
                       (hash3((int)k, 2, 0, 5) % 1000) / 100.0};
        append(m, k % 2 ? ball : cube, at, 0.2 + (hash3((int)k, 3, 0, 5) % 100) / 200.0);
    }
    return m;
}

// ---- assimp: normals and texture coordinates ----------------------------------
std::string to_obj(const Mesh &m)
{
    std::string s;
    char line[128];
    for (const V3 &p : m.v) {
        std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", p.x, p.y, p.z);
        s += line;
    }
    for (size_t i = 0; i < m.f.size(); i += 3) {
        std::snprintf(line, sizeof line, "f %u %u %u\n", m.f[i] + 1, m.f[i + 1] + 1, m.f[i + 2] + 1);
        s += line;
    }
    return s;
}

const aiScene *with_attributes(Assimp::Importer &imp, const std::string &obj, const char *path,
                               aiTextureMapping mapping)
{
    imp.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, 80.0f);
    const unsigned steps = aiProcess_Triangulate | aiProcess_GenSmoothNormals |
                           aiProcess_ValidateDataStructure;
    const aiScene *sc = path ? imp.ReadFile(path, steps)
                             : imp.ReadFileFromMemory(obj.data(), obj.size(), steps, "obj");
    if (!sc || sc->mNumMeshes != 1 || sc->mNumMaterials < 1)
        return nullptr;
    aiMaterial *mat = sc->mMaterials[sc->mMeshes[0]->mMaterialIndex];
    const aiString tex("uv.png");
    const int map = mapping;
    const aiVector3D axis(0, 1, 0);
    mat->AddProperty(&tex, AI_MATKEY_TEXTURE_DIFFUSE(0));
    mat->AddProperty(&map, 1, AI_MATKEY_MAPPING_DIFFUSE(0));
    mat->AddProperty(&axis, 1, AI_MATKEY_TEXMAP_AXIS_DIFFUSE(0));
    sc = imp.ApplyPostProcessing(aiProcess_GenUVCoords | aiProcess_JoinIdenticalVertices);
    if (!sc || !sc->mMeshes[0]->HasNormals() || !sc->mMeshes[0]->HasTextureCoords(0))
        return nullptr;
    return sc;
}

struct Key {
    float x, y, z;
    bool operator<(const Key &o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
};

bool write_files(const aiMesh *am, const std::string &base)
{
    // positions shared by corners: one OBJ v per distinct position
    std::map<Key, uint32_t> ids;
    std::vector<uint32_t> pos_of(am->mNumVertices);
    std::vector<uint32_t> first;  // an assimp vertex per position
    for (unsigned i = 0; i < am->mNumVertices; ++i) {
        const aiVector3D &p = am->mVertices[i];
        auto it = ids.emplace(Key{p.x, p.y, p.z}, (uint32_t)first.size());
        if (it.second)
            first.push_back(i);
        pos_of[i] = it.first->second;
    }
    for (int with_uv = 0; with_uv <= 1; ++with_uv) {
        FILE *f = std::fopen((base + (with_uv ? "_nt.obj" : "_n.obj")).c_str(), "w");
        if (!f)
            return false;
        for (uint32_t i : first)
            std::fprintf(f, "v %.6f %.6f %.6f\n", am->mVertices[i].x, am->mVertices[i].y, am->mVertices[i].z);
        for (unsigned i = 0; i < am->mNumVertices; ++i) {
            const aiVector3D &n = am->mNormals[i];
            std::fprintf(f, "vn %.6f %.6f %.6f\n", n.x, n.y, n.z);
            if (with_uv)
                std::fprintf(f, "vt %.6f %.6f\n", am->mTextureCoords[0][i].x, am->mTextureCoords[0][i].y);
        }
        for (unsigned k = 0; k < am->mNumFaces; ++k) {
            const aiFace &fc = am->mFaces[k];
            if (fc.mNumIndices != 3)
                continue;
            std::fputc('f', f);
            for (int c = 0; c < 3; ++c) {
                const unsigned i = fc.mIndices[c];
                if (with_uv)
                    std::fprintf(f, " %u/%u/%u", pos_of[i] + 1, i + 1, i + 1);
                else
                    std::fprintf(f, " %u//%u", pos_of[i] + 1, i + 1);
            }
            std::fputc('\n', f);
        }
        if (std::fclose(f))
            return false;
    }
    // colours: per position, from its (first) normal and a band of height
    FILE *f = std::fopen((base + "_c.ply").c_str(), "w");
    if (!f)
        return false;
    unsigned nf = 0;
    for (unsigned k = 0; k < am->mNumFaces; ++k)
        nf += am->mFaces[k].mNumIndices == 3;
    std::fprintf(f, "ply\nformat ascii 1.0\nelement vertex %zu\nproperty float x\nproperty float y\n"
                    "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                    "element face %u\nproperty list uchar int vertex_indices\nend_header\n",
                 first.size(), nf);
    for (uint32_t i : first) {
        const aiVector3D &p = am->mVertices[i], &n = am->mNormals[i];
        const double band = 0.5 + 0.5 * std::sin(p.y * 12.0);
        std::fprintf(f, "%.6f %.6f %.6f %d %d %d\n", p.x, p.y, p.z, (int)(127.5 + 127 * n.x),
                     (int)(40 + 200 * band), (int)(127.5 + 127 * n.z));
    }
    for (unsigned k = 0; k < am->mNumFaces; ++k) {
        const aiFace &fc = am->mFaces[k];
        if (fc.mNumIndices == 3)
            std::fprintf(f, "3 %u %u %u\n", pos_of[fc.mIndices[0]], pos_of[fc.mIndices[1]],
                         pos_of[fc.mIndices[2]]);
    }
    return std::fclose(f) == 0;
}

bool make(const std::string &dir, const char *name, const Mesh *m, const char *path,
          aiTextureMapping mapping)
{
    Assimp::Importer imp;
    const aiScene *sc = with_attributes(imp, m ? to_obj(*m) : std::string(), path, mapping);
    if (!sc) {
        std::fprintf(stderr, "gen-attr-meshes: %s: assimp: %s\n", name, imp.GetErrorString());
        return false;
    }
    if (!write_files(sc->mMeshes[0], dir + "/" + name)) {
        std::fprintf(stderr, "gen-attr-meshes: %s: cannot write in %s\n", name, dir.c_str());
        return false;
    }
    return true;
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc != 2 && argc != 3) {
        std::fprintf(stderr, "usage: gen-attr-meshes OUTDIR [BUNNY.obj]\n");
        return 2;
    }
    const std::string dir = argv[1];
    const Mesh s20 = scan(5, 1), s82 = scan(6, 2), ter = terrain(121), gear = cad(), tor = holed(),
               many = parts();
    bool ok = make(dir, "scan_20k", &s20, nullptr, aiTextureMapping_SPHERE) &&
              make(dir, "scan_82k", &s82, nullptr, aiTextureMapping_SPHERE) &&
              make(dir, "terrain", &ter, nullptr, aiTextureMapping_PLANE) &&
              make(dir, "cad", &gear, nullptr, aiTextureMapping_CYLINDER) &&
              make(dir, "holed", &tor, nullptr, aiTextureMapping_SPHERE) &&
              make(dir, "parts", &many, nullptr, aiTextureMapping_SPHERE);
    if (ok && argc == 3)
        ok = make(dir, "bunny", nullptr, argv[2], aiTextureMapping_SPHERE);
    return ok ? 0 : 1;
}

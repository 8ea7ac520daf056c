// Stable-fluids wind solver (see fluid.h).
#include "fluid.h"

#include "core/error.h"
#include "float4.h"
#include "parallel.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

namespace meadow {

namespace {

constexpr float kDirectionEpsilon = 1e-4f;    // a face is upwind when the wind enters it this steeply
constexpr float kDivergenceTolerance = 7e-4f; // max |div u| * h / U after projection
constexpr float kMinReferenceSpeed = 0.1f;    // m/s, tolerance scale for calm levels
constexpr int kMaxPressureCycles = 12;
constexpr float kVonKarman = 0.41f;
constexpr float kGroundRoughness = 0.01f; // m, z0 of short vegetation

std::array<bool, 6> upwindFaces(const WindLevelParams& level) {
    glm::vec3 d{level.direction.x, 0.0f, level.direction.z};
    d /= glm::length(d);
    // The wind enters through the -x face when it blows towards +x, and so on.
    return {d.x > kDirectionEpsilon, d.x<-kDirectionEpsilon, false, false, d.z> kDirectionEpsilon,
            d.z < -kDirectionEpsilon};
}

std::array<bool, 6> openFaces(const std::array<bool, 6>& upwind) {
    // Upwind faces prescribe velocity, ground and top are walls: pressure Neumann. The rest are open.
    return {!upwind[0], !upwind[1], false, false, !upwind[4], !upwind[5]};
}

const WindLevelParams& validated(const FluidGrid& grid, const WindLevelParams& level) {
    auto fail = [](const std::string& what) { throw Error("wind solver: " + what); };
    if (grid.cells.x < 2 || grid.cells.y < 2 || grid.cells.z < 2) {
        fail("grid needs at least 2 cells per axis, got " + std::to_string(grid.cells.x) + "x" +
             std::to_string(grid.cells.y) + "x" + std::to_string(grid.cells.z));
    }
    if (!(grid.cellSize > 0.0f) || !std::isfinite(grid.cellSize)) {
        fail("cell size must be positive, got " + std::to_string(grid.cellSize));
    }
    if (!std::isfinite(grid.origin.x) || !std::isfinite(grid.origin.y) || !std::isfinite(grid.origin.z)) {
        fail("grid origin is not finite");
    }
    float horizontal = std::hypot(level.direction.x, level.direction.z);
    if (!(horizontal > 1e-6f) || !std::isfinite(horizontal)) {
        fail("wind direction needs a horizontal component");
    }
    if (!(level.meanSpeed >= 0.0f) || !std::isfinite(level.meanSpeed)) {
        fail("mean speed must be >= 0 m/s, got " + std::to_string(level.meanSpeed));
    }
    if (!(level.turbulence >= 0.0f) || !std::isfinite(level.turbulence)) {
        fail("turbulence must be >= 0, got " + std::to_string(level.turbulence));
    }
    if (!(level.gustPeriod > 0.0f) || !std::isfinite(level.gustPeriod)) {
        fail("gust period must be > 0 s, got " + std::to_string(level.gustPeriod));
    }
    return level;
}

// Trilinear interpolation on a dims-sized sample lattice, split into the corner/weights setup and
// the 8-point blend so that several arrays on one lattice share a setup. f is clamped into the
// lattice (constant extrapolation beyond the outermost samples).
struct Trilinear {
    size_t base;
    size_t strideY;
    size_t strideZ;
    float tx, ty, tz;

    Trilinear(glm::ivec3 dims, float fx, float fy, float fz) {
        // min/max rather than std::clamp: branch-free (minss/maxss) in the advection loop.
        fx = std::min(std::max(fx, 0.0f), static_cast<float>(dims.x - 1));
        fy = std::min(std::max(fy, 0.0f), static_cast<float>(dims.y - 1));
        fz = std::min(std::max(fz, 0.0f), static_cast<float>(dims.z - 1));
        int i = std::min(static_cast<int>(fx), dims.x - 2);
        int j = std::min(static_cast<int>(fy), dims.y - 2);
        int k = std::min(static_cast<int>(fz), dims.z - 2);
        tx = fx - static_cast<float>(i);
        ty = fy - static_cast<float>(j);
        tz = fz - static_cast<float>(k);
        strideY = static_cast<size_t>(dims.x);
        strideZ = static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y);
        base = static_cast<size_t>(i) + strideY * static_cast<size_t>(j) + strideZ * static_cast<size_t>(k);
    }

    float operator()(const float* a) const {
        const float* p = a + base;
        float x00 = p[0] + tx * (p[1] - p[0]);
        float x10 = p[strideY] + tx * (p[strideY + 1] - p[strideY]);
        float x01 = p[strideZ] + tx * (p[strideZ + 1] - p[strideZ]);
        float x11 = p[strideZ + strideY] + tx * (p[strideZ + strideY + 1] - p[strideZ + strideY]);
        float y0 = x00 + ty * (x10 - x00);
        float y1 = x01 + ty * (x11 - x01);
        return y0 + tz * (y1 - y0);
    }
};

// The path velocity's three components blend together (float4.h): a third of the scalar work.
Float4 trilinear4(const glm::vec4* a, const Trilinear& l) {
    const glm::vec4* p = a + l.base;
    const size_t sy = l.strideY;
    const size_t sz = l.strideZ;
    Float4 x00 = load4(p[0]) + l.tx * (load4(p[1]) - load4(p[0]));
    Float4 x10 = load4(p[sy]) + l.tx * (load4(p[sy + 1]) - load4(p[sy]));
    Float4 x01 = load4(p[sz]) + l.tx * (load4(p[sz + 1]) - load4(p[sz]));
    Float4 x11 = load4(p[sz + sy]) + l.tx * (load4(p[sz + sy + 1]) - load4(p[sz + sy]));
    Float4 y0 = x00 + l.ty * (x10 - x00);
    Float4 y1 = x01 + l.ty * (x11 - x01);
    return y0 + l.tz * (y1 - y0);
}

float trilinear(const std::vector<float>& a, glm::ivec3 dims, glm::vec3 f) {
    return Trilinear(dims, f.x, f.y, f.z)(a.data());
}

} // namespace

WindSolver::WindSolver(const FluidGrid& grid, const WindLevelParams& level)
    : grid_(grid), level_(validated(grid, level)), inflow_(grid, level), n_(grid.cells), h_(grid.cellSize),
      inflowFace_(upwindFaces(level)), pressure_(grid.cells, openFaces(upwindFaces(level))) {
    level_.direction = inflow_.direction();
    for (int axis = 0; axis < 3; ++axis) {
        glm::ivec3 dims = n_;
        dims[axis] += 1;
        glm::vec3 offset{0.5f};
        offset[axis] = 0.0f;
        size_t count = static_cast<size_t>(dims.x) * dims.y * dims.z;
        for (FaceGrid* face : {&velocity_[axis], &advected_[axis], &force_[axis]}) {
            face->dims = dims;
            face->offset = offset;
            face->values.assign(count, 0.0f);
        }
    }
    cellVelocity_.assign(static_cast<size_t>(n_.x) * n_.y * n_.z, glm::vec4(0.0f));

    // Start from the ambient wind so that no spin-up from rest is needed, then make it
    // divergence-free.
    for (int axis = 0; axis < 3; ++axis) {
        FaceGrid& face = velocity_[axis];
        for (int k = 0; k < face.dims.z; ++k) {
            for (int j = 0; j < face.dims.y; ++j) {
                for (int i = 0; i < face.dims.x; ++i) {
                    glm::vec3 p = grid_.origin + h_ * (glm::vec3(i, j, k) + face.offset);
                    face.values[face.index(i, j, k)] = inflow_.velocity(p, 0.0)[axis];
                }
            }
        }
    }
    applyBoundaries();
    project();
}

bool WindSolver::outsideSides(glm::vec3 c) const {
    return c.x < 0.0f || c.x > static_cast<float>(n_.x) || c.z < 0.0f || c.z > static_cast<float>(n_.z);
}

// Velocity along a backtrace path. Above the lid or below the ground the position is clamped
// (those faces are walls); beyond a side face the ambient wind holds.
glm::vec3 WindSolver::samplePathVelocity(glm::vec3 c) const {
    if (outsideSides(c)) {
        return inflow_.fastVelocity(grid_.origin + h_ * c);
    }
    Float4 v = trilinear4(cellVelocity_.data(), Trilinear(n_, c.x - 0.5f, c.y - 0.5f, c.z - 0.5f));
    return {v[0], v[1], v[2]};
}

float WindSolver::sampleComponent(const FaceGrid& face, int axis, glm::vec3 c) const {
    if (outsideSides(c)) {
        return inflow_.fastVelocity(grid_.origin + h_ * c)[axis];
    }
    return Trilinear(face.dims, c.x - face.offset.x, c.y - face.offset.y, c.z - face.offset.z)(face.values.data());
}

void WindSolver::addForce(glm::vec3 p, glm::vec3 force) {
    glm::vec3 c = (p - grid_.origin) / h_;
    // Written so that NaN coordinates or forces are ignored instead of indexing garbage.
    if (!(c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f && c.x <= static_cast<float>(n_.x) &&
          c.y <= static_cast<float>(n_.y) && c.z <= static_cast<float>(n_.z)) ||
        !std::isfinite(force.x) || !std::isfinite(force.y) || !std::isfinite(force.z)) {
        return;
    }
    hasForce_ = true;
    for (int axis = 0; axis < 3; ++axis) {
        FaceGrid& face = force_[axis];
        glm::vec3 f = glm::clamp(c - face.offset, glm::vec3(0.0f), glm::vec3(face.dims - 1));
        glm::ivec3 i0 = glm::min(glm::ivec3(f), face.dims - 2);
        glm::vec3 t = f - glm::vec3(i0);
        for (int corner = 0; corner < 8; ++corner) {
            glm::ivec3 o{corner & 1, (corner >> 1) & 1, corner >> 2};
            float weight = (o.x ? t.x : 1.0f - t.x) * (o.y ? t.y : 1.0f - t.y) * (o.z ? t.z : 1.0f - t.z);
            face.values[face.index(i0.x + o.x, i0.y + o.y, i0.z + o.z)] += weight * force[axis];
        }
    }
}

// Body force: each face holds the air of one cell, so its acceleration is F / (rho h^3).
void WindSolver::applyForces(float dt) {
    if (!hasForce_) {
        return;
    }
    float scale = dt / (kAirDensity * h_ * h_ * h_);
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<float>& v = velocity_[axis].values;
        std::vector<float>& f = force_[axis].values;
        for (size_t i = 0; i < v.size(); ++i) {
            v[i] += scale * f[i];
            f[i] = 0.0f;
        }
    }
    hasForce_ = false;
}

void WindSolver::updateCellVelocity() {
    const FaceGrid& u = velocity_[0];
    const FaceGrid& v = velocity_[1];
    const FaceGrid& w = velocity_[2];
    forEachSlab(n_.z, n_.x * n_.y, [&](int k0, int k1) {
        const size_t vy = static_cast<size_t>(n_.x);
        const size_t wz = static_cast<size_t>(n_.x) * n_.y;
        for (int k = k0; k < k1; ++k) {
            for (int j = 0; j < n_.y; ++j) {
                size_t c = static_cast<size_t>(n_.x) * (static_cast<size_t>(j) + static_cast<size_t>(n_.y) * k);
                size_t iu = u.index(0, j, k);
                size_t iv = v.index(0, j, k);
                size_t iw = w.index(0, j, k);
                for (int i = 0; i < n_.x; ++i, ++c, ++iu, ++iv, ++iw) {
                    cellVelocity_[c] =
                        glm::vec4(0.5f * (u.values[iu] + u.values[iu + 1]), 0.5f * (v.values[iv] + v.values[iv + vy]),
                                  0.5f * (w.values[iw] + w.values[iw + wz]), 0.0f);
                }
            }
        }
    });
}

// Semi-Lagrangian advection (Stam 1999, section 3.2): each face takes the value found by tracing
// its position back through the velocity field; RK2 midpoint for the path. The path starts from
// the average of the two cells beside the face.
template <int Axis> void WindSolver::advectAxis(float dt) {
    const float back = dt / h_; // cell units per (m/s)
    const FaceGrid& source = velocity_[Axis];
    FaceGrid& target = advected_[Axis];
    const glm::ivec3 dims = source.dims;
    const int last = n_[Axis];
    const size_t cellStride[3] = {1, static_cast<size_t>(n_.x), static_cast<size_t>(n_.x) * n_.y};
    forEachSlab(dims.z, dims.x * dims.y, [&](int k0, int k1) {
        const glm::vec4* cells = cellVelocity_.data();
        for (int k = k0; k < k1; ++k) {
            for (int j = 0; j < dims.y; ++j) {
                size_t index = source.index(0, j, k);
                for (int i = 0; i < dims.x; ++i, ++index) {
                    const int face[3] = {i, j, k};
                    const int along = face[Axis];
                    int cell[3] = {i, j, k};
                    cell[Axis] = std::min(along, last - 1);
                    size_t c = static_cast<size_t>(cell[0]) + cellStride[1] * static_cast<size_t>(cell[1]) +
                               cellStride[2] * static_cast<size_t>(cell[2]);
                    size_t before = along > 0 && along < last ? c - cellStride[Axis] : c;
                    glm::vec3 start = glm::vec3(cells[c]) + glm::vec3(cells[before]);
                    glm::vec3 x =
                        glm::vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) + source.offset;
                    glm::vec3 mid = x - (0.25f * back) * start; // start holds twice the average
                    glm::vec3 from = x - back * samplePathVelocity(mid);
                    target.values[index] = sampleComponent(source, Axis, from);
                }
            }
        }
    });
}

void WindSolver::advect(float dt) {
    advectAxis<0>(dt);
    advectAxis<1>(dt);
    advectAxis<2>(dt);
    for (int axis = 0; axis < 3; ++axis) {
        std::swap(velocity_[axis].values, advected_[axis].values);
    }
}

// Log-law wall function on the first cell layer: du/dt = -C_d |u| u / h, taken implicitly
// (u / (1 + dt C_d |u| / h)) so that it can only slow the air, never reverse it.
void WindSolver::applyGroundStress(float dt) {
    float z1 = 0.5f * h_;
    float logTerm = std::log(std::max(z1 / kGroundRoughness, 2.0f));
    float dragCoefficient = (kVonKarman / logTerm) * (kVonKarman / logTerm);
    float rate = dt * dragCoefficient / h_;
    for (int axis : {0, 2}) {
        FaceGrid& face = velocity_[axis];
        for (int k = 0; k < face.dims.z; ++k) {
            for (int i = 0; i < face.dims.x; ++i) {
                // Horizontal speed from the (pre-advection) cell velocities beside the face.
                glm::ivec3 a{std::min(i, n_.x - 1), 0, std::min(k, n_.z - 1)};
                glm::ivec3 b = a;
                b[axis] = std::max((axis == 0 ? i : k) - 1, 0);
                size_t ia = static_cast<size_t>(a.x) + static_cast<size_t>(n_.x) * n_.y * a.z;
                size_t ib = static_cast<size_t>(b.x) + static_cast<size_t>(n_.x) * n_.y * b.z;
                float speed = 0.5f * std::hypot(cellVelocity_[ia].x + cellVelocity_[ib].x,
                                                cellVelocity_[ia].z + cellVelocity_[ib].z);
                face.values[face.index(i, 0, k)] /= 1.0f + rate * speed;
            }
        }
    }
}

// Prescribed normal velocities: the ambient wind on upwind faces, zero through ground and top.
void WindSolver::applyBoundaries() {
    for (int axis : {0, 2}) {
        FaceGrid& face = velocity_[axis];
        for (int side = 0; side < 2; ++side) {
            if (!inflowFace_[2 * axis + side]) {
                continue;
            }
            int layer = side == 0 ? 0 : n_[axis];
            int other = axis == 0 ? 2 : 0;
            for (int b = 0; b < n_[other]; ++b) {
                for (int j = 0; j < n_.y; ++j) {
                    glm::ivec3 c{0, j, 0};
                    c[axis] = layer;
                    c[other] = b;
                    glm::vec3 p = grid_.origin + h_ * (glm::vec3(c) + face.offset);
                    face.values[face.index(c.x, c.y, c.z)] = inflow_.fastVelocity(p)[axis];
                }
            }
        }
    }
    FaceGrid& v = velocity_[1];
    for (int k = 0; k < n_.z; ++k) {
        for (int i = 0; i < n_.x; ++i) {
            v.values[v.index(i, 0, k)] = 0.0f;
            v.values[v.index(i, n_.y, k)] = 0.0f;
        }
    }
}

// Projection (Stam 1999, section 3.1; Helmholtz-Hodge): solve A phi = -h D with D the net outflow
// of each cell (m/s) and phi = p dt / rho, then u -= grad phi. The cell's divergence afterwards is
// exactly -residual / h^2, so the multigrid tolerance bounds max |div u| directly.
void WindSolver::project() {
    const FaceGrid& u = velocity_[0];
    const FaceGrid& v = velocity_[1];
    const FaceGrid& w = velocity_[2];
    std::vector<float>& rhs = pressure_.rhs();
    const size_t vy = static_cast<size_t>(n_.x);
    const size_t wz = static_cast<size_t>(n_.x) * n_.y;
    auto divergenceSum = [&](int i, int j, int k) {
        size_t iu = u.index(i, j, k);
        size_t iv = v.index(i, j, k);
        size_t iw = w.index(i, j, k);
        return (u.values[iu + 1] - u.values[iu]) + (v.values[iv + vy] - v.values[iv]) +
               (w.values[iw + wz] - w.values[iw]);
    };
    forEachSlab(n_.z, n_.x * n_.y, [&](int k0, int k1) {
        for (int k = k0; k < k1; ++k) {
            for (int j = 0; j < n_.y; ++j) {
                for (int i = 0; i < n_.x; ++i) {
                    rhs[pressure_.index(i, j, k)] = -h_ * divergenceSum(i, j, k);
                }
            }
        }
    });
    float referenceSpeed = std::max(level_.meanSpeed, kMinReferenceSpeed);
    lastPressureCycles_ = pressure_.solve(kDivergenceTolerance * referenceSpeed * h_, kMaxPressureCycles);

    // u -= grad phi on every face that is not prescribed; the ghost phi beyond an open face is 0.
    const std::vector<float>& phi = pressure_.phi();
    const glm::ivec3 strides = pressure_.strides();
    const float inverseH = 1.0f / h_;
    for (int axis = 0; axis < 3; ++axis) {
        FaceGrid& face = velocity_[axis];
        const size_t stride = static_cast<size_t>(strides[axis]);
        // Faces first..last along the axis are updated; prescribed ones (walls, inflow) are not.
        const int first = inflowFace_[2 * axis] || axis == 1 ? 1 : 0;
        const int last = inflowFace_[2 * axis + 1] || axis == 1 ? n_[axis] - 1 : n_[axis];
        const glm::ivec3 lo{axis == 0 ? first : 0, axis == 1 ? first : 0, axis == 2 ? first : 0};
        const glm::ivec3 hi{axis == 0 ? last : face.dims.x - 1, axis == 1 ? last : face.dims.y - 1,
                            axis == 2 ? last : face.dims.z - 1};
        forEachSlab(hi.z - lo.z + 1, face.dims.x * face.dims.y, [&](int k0, int k1) {
            for (int k = lo.z + k0; k < lo.z + k1; ++k) {
                for (int j = lo.y; j <= hi.y; ++j) {
                    // Face i lies between cells i - 1 and i (along the axis); phi is padded.
                    float* value = &face.values[face.index(lo.x, j, k)];
                    const float* right = &phi[pressure_.index(lo.x, j, k)];
                    const float* left = right - stride;
                    for (int i = 0; i <= hi.x - lo.x; ++i) {
                        value[i] -= (right[i] - left[i]) * inverseH;
                    }
                }
            }
        });
    }

    double maxAbs = 0.0;
    for (int k = 0; k < n_.z; ++k) {
        for (int j = 0; j < n_.y; ++j) {
            for (int i = 0; i < n_.x; ++i) {
                maxAbs = std::max(maxAbs, static_cast<double>(std::abs(divergenceSum(i, j, k))));
            }
        }
    }
    maxDivergence_ = maxAbs / h_;
}

void WindSolver::step(float dt) {
    assert(dt > 0.0f && std::isfinite(dt));
    inflow_.prepare(time_); // backtraces leaving the box meet the ambient wind of the step's start
    applyForces(dt);
    updateCellVelocity();
    advect(dt);
    applyGroundStress(dt);
    time_ += dt;
    inflow_.prepare(time_);
    applyBoundaries();
    project();
}

glm::vec3 WindSolver::velocityAt(glm::vec3 p) const {
    glm::vec3 c = (p - grid_.origin) / h_;
    // Written so that NaN coordinates also take the outside branch instead of indexing garbage.
    if (!(c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f && c.x <= static_cast<float>(n_.x) &&
          c.y <= static_cast<float>(n_.y) && c.z <= static_cast<float>(n_.z))) {
        return inflowVelocity(p);
    }
    return {trilinear(velocity_[0].values, velocity_[0].dims, c - velocity_[0].offset),
            trilinear(velocity_[1].values, velocity_[1].dims, c - velocity_[1].offset),
            trilinear(velocity_[2].values, velocity_[2].dims, c - velocity_[2].offset)};
}

glm::vec3 WindSolver::inflowVelocity(glm::vec3 p) const {
    return inflow_.velocity(p, time_);
}

float WindSolver::inflowProfile(float height) const {
    return inflow_.profileSpeed(height);
}

// Faces on the box boundary hold half a cell of air inside the box; fixed summation order.
double WindSolver::kineticEnergy() const {
    double sum = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const FaceGrid& face = velocity_[axis];
        for (int k = 0; k < face.dims.z; ++k) {
            for (int j = 0; j < face.dims.y; ++j) {
                for (int i = 0; i < face.dims.x; ++i) {
                    int along = glm::ivec3(i, j, k)[axis];
                    double weight = along == 0 || along == n_[axis] ? 0.5 : 1.0;
                    double value = face.values[face.index(i, j, k)];
                    sum += weight * value * value;
                }
            }
        }
    }
    double cellVolume = static_cast<double>(h_) * h_ * h_;
    return 0.5 * kAirDensity * sum * cellVolume;
}

} // namespace meadow

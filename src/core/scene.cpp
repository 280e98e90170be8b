#include "obscura/scene.hpp"

#include <algorithm>

namespace obscura {

Bounds sceneBounds(const Scene& scene) {
    Bounds b;
    for (const Mesh& mesh : scene.meshes) {
        if (!mesh.data) continue;
        for (const glm::vec3& p : mesh.data->positions) {
            const glm::vec3 w = glm::vec3(mesh.model * glm::vec4(p, 1.0f));
            if (b.empty) {
                b.min = b.max = w;
                b.empty = false;
            } else {
                b.min = glm::min(b.min, w);
                b.max = glm::max(b.max, w);
            }
        }
    }
    return b;
}

} // namespace obscura

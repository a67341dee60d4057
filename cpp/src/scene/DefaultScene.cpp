#include <weft/Scene.h>

#include <cmath>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

namespace weft {

namespace {

// A woven-looking check pattern: two thread colours with soft thread edges.
TexturePtr makeClothTexture(int size) {
    ImageU8 img(size, size, 4);
    const int cell = size / 16;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const bool warp = ((x / cell) + (y / cell)) % 2 == 0;
            const float fx = float(x % cell) / float(cell), fy = float(y % cell) / float(cell);
            const float thread = 0.8f + 0.2f * std::sin(3.14159f * (warp ? fx : fy));
            const glm::vec3 a(0.80f, 0.74f, 0.62f), b(0.36f, 0.42f, 0.55f);
            const glm::vec3 c = (warp ? a : b) * thread;
            uint8_t* p = img.at(x, y);
            for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::lround(255.0f * c[k]));
            p[3] = 255;
        }
    }
    return std::make_shared<Texture>(std::move(img), true, true);
}

} // namespace

void makeDefaultScene(Scene& scene, Camera& camera) {
    Material ground;
    ground.texture = makeClothTexture(256);
    ground.ks = glm::vec3(0.05f);
    ground.shininess = 16.0f;
    scene.addMesh(std::make_shared<Mesh>(Mesh::plane(8.0f, 8.0f, 4, 4)), ground);

    Material sphere;
    sphere.baseColor = glm::vec3(0.75f, 0.18f, 0.15f);
    sphere.ks = glm::vec3(0.5f);
    sphere.shininess = 48.0f;
    scene.addMesh(std::make_shared<Mesh>(Mesh::uvSphere(0.75f, 48, 24)), sphere,
                  glm::translate(glm::mat4(1.0f), glm::vec3(-0.9f, 0.75f, 0.0f)));

    Material box;
    box.baseColor = glm::vec3(0.2f, 0.55f, 0.3f);
    box.ks = glm::vec3(0.2f);
    box.shininess = 24.0f;
    glm::mat4 boxTransform = glm::translate(glm::mat4(1.0f), glm::vec3(1.1f, 0.5f, 0.4f));
    boxTransform = glm::rotate(boxTransform, 0.6f, glm::vec3(0, 1, 0));
    scene.addMesh(std::make_shared<Mesh>(Mesh::box(glm::vec3(1.0f))), box, boxTransform);

    DirectionalLight sun;
    sun.direction = glm::vec3(-0.5f, -1.0f, -0.35f);
    sun.color = glm::vec3(1.0f, 0.96f, 0.88f);
    sun.intensity = 0.9f;
    scene.addLight(sun);
    scene.setAmbient(glm::vec3(0.18f, 0.2f, 0.24f));
    scene.setBackground(glm::vec3(0.38f, 0.55f, 0.8f));

    camera = Camera{};
    camera.position = glm::vec3(0.5f, 2.6f, 5.2f);
    camera.target = glm::vec3(0.0f, 0.4f, 0.0f);
}

} // namespace weft

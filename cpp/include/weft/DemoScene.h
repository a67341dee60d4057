#pragma once
// The seed's interactive environment (SPEC §1.6, §2): a terrain from a height map that the
// cloth collides with, a sphere, a cloth held at one edge in the wind, a sun and a moon in a
// day-night cycle, and the user's controls (grab and drag the cloth, wind, light, toggles).
#include <memory>
#include <string>
#include <vector>

#include <weft/Camera.h>
#include <weft/Cloth.h>
#include <weft/Environment.h>
#include <weft/Renderer.h>
#include <weft/Scene.h>

namespace weft::app {

class DemoScene {
public:
    DemoScene();

    Scene& scene() { return mScene; }
    Camera& camera() { return mCamera; }
    const Cloth& cloth() const { return *mCloth; }
    std::shared_ptr<Cloth> clothPtr() const { return mCloth; }
    /// Lights the scene with a captured environment instead of the sun and moon: an
    /// equirectangular (2:1) or sphere-map (square) .hdr/.exr/.png, diffuse from its SH9
    /// irradiance and shadows from a dome of 16 lights (SPEC §4.4, §4.5).
    void lightWith(const std::string& path);
    /// Sets the time of day in hours [0, 24] (6 sunrise, 12 noon, 18 sunset) and the sky.
    void setHour(float hour);
    /// Milliseconds the last analytic sky took (cube, dome texture and sun light).
    double skyMs() const { return mSkyMs; }
    /// Renderer settings the controls change (PCF kernel).
    void applySettings(Renderer& renderer) const;

    /// Advances the simulation by real time (fixed 60 Hz steps, at most 8 per call) and the
    /// day-night cycle; returns the simulation steps run.
    int update(float realDt);

    /// A key (GLFW key code) pressed; returns a one-line description of what changed, or "".
    std::string key(int glfwKey);
    /// Grabs the cloth particle nearest to the ray through pixel (x, y) of a w x h image.
    bool grab(double x, double y, int w, int h);
    /// Moves the grabbed particle along the plane through it facing the camera.
    void drag(double x, double y, int w, int h);
    void release();
    bool grabbing() const { return mGrabbed >= 0; }

    // The controls' state, read and set by the settings (DemoSettings.h) and weft-demo's panel.
    float windStrength() const { return mWindStrength; }
    float windDirection() const; ///< degrees in [0, 360)
    void setWind(float strength, float directionDegrees);
    float lightAzimuth() const; ///< degrees in [0, 360): where the sun and moon circle
    void setLightAzimuth(float degrees);
    float hour() const { return 24.0f * mTimeOfDay; }
    bool environmentLit() const { return mEnvironmentLit; }
    bool dayNight() const { return mDayNight; }
    bool paused() const { return mPaused; }
    bool normalMap() const { return mNormalMap; }
    bool holes() const { return mHoles; }
    bool shadows() const { return mShadows; }
    bool btf() const { return mBtf; }
    bool reflections() const { return mReflections; }
    int furModel() const { return mFurModel; } ///< 0 Kajiya-Kay, 1 Marschner, 2 Sadeghi
    int pcf() const { return mPcf; }           ///< PCF radius 0..3 (kernel 2r+1)

    /// One line of the controls for the help text.
    static const char* controls();
    /// The state in one line (wind, time of day, toggles) for titles and logs.
    std::string status() const;

private:
    void buildTerrain();
    void updateSky();
    void useEnvironmentDiffuse();
    void ray(double x, double y, int w, int h, glm::vec3& origin, glm::vec3& dir) const;

    Scene mScene;
    Camera mCamera;
    std::shared_ptr<Cloth> mCloth;
    uint32_t mClothId = 0;
    Material mClothMaterial;
    TexturePtr mWeaveNormals;
    uint32_t mSunId = 0, mMoonId = 0, mTerrainId = 0;
    Material mTerrainMaterial;
    glm::vec3 mGroundAlbedo{0.2f}; // the grass texture's mean linear colour
    bool mEnvironmentLit = false;
    std::shared_ptr<Environment> mSky; // the analytic sky (null with a captured environment)
    glm::vec3 mSkySun{0.0f};           // the sun it was generated for
    DirectionalLight mSunLight;        // its sun
    double mSkyMs = 0.0;
    uint32_t mBallId = 0;
    Material mBallMaterial;
    float mSunAzimuth = 0.6f;
    float mTimeOfDay = 0.35f; // 0..1, 0.25 = sunrise... 0.5 = noon (the sun at its highest)
    bool mDayNight = false, mPaused = false, mNormalMap = true, mHoles = false;
    bool mShadows = true;
    bool mBtf = false;
    bool mReflections = false;
    uint32_t mFurId = 0;
    int mFurModel = 0; // Kajiya-Kay, Marschner, Sadeghi
    HairMaterial mFurMaterial;
    uint32_t mSphereId = 0;
    Material mSphereMaterial;
    std::unique_ptr<Material> mBtfMaterial; // fitted on first use
    int mPcf = 1;
    float mWindStrength = 3.0f, mWindAngle = 0.4f;
    int mGrabbed = -1;
    float mGrabDepth = 0.0f; // distance of the grab plane along the view direction
};

} // namespace weft::app

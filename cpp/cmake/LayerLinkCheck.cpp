// The main of the layer link checks (cpp/cmake/WeftLayers.cmake): what matters is that the
// subsystem's objects and those below it link alone, not what runs.
int main() { return 0; }

// Sanitizer builds only: cmake/Sanitizers.cmake links this into every executable the project
// builds. dlclose does nothing, so the Vulkan driver (lavapipe and its LLVM) and the layers the
// loader unloads at vkDestroyInstance stay mapped until exit, when LeakSanitizer looks. Still
// mapped, their globals keep their one-time allocations reachable, and what they do leak is
// reported with their library's name, which tests/sanitizers/lsan.supp can match. Unloaded,
// those allocations would be reported under "<unknown module>", or under whichever library was
// mapped at the same address later, and no suppression could tell them from ours.
extern "C" int dlclose(void*) { return 0; }

// Khronos validation layer 1.3.239 keeps about 10 kB of its own state per pipeline-creating
// device after vkDestroyDevice (indirect leaks inside libVkLayer_khronos_validation.so, with
// the layer itself reporting no object of ours left alive; the same run without the layer is
// clean). Read by LeakSanitizer in sanitizer builds; an unused weak hook otherwise.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libVkLayer_khronos_validation.so\n"; }

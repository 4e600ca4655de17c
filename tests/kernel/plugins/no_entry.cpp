// A shared library that is not a medax plugin: it exports a function but no medax_plugin_entry.
extern "C" __attribute__((visibility("default"))) int kernel_test_not_a_plugin() { return 42; }

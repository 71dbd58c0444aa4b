/* LD_PRELOADed by `make faults-asan`: dlclose keeps every library loaded, so that the leak
   checker at exit can still name the module of each allocation (the Vulkan loader closes the
   driver and the layers before then, and their leaks would read "<unknown module>"). */
int dlclose(void* handle) {
    (void)handle;
    return 0;
}

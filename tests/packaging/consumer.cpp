// Built against an installed pathpace via find_package(pathpace); exits non-zero on failure.
#include <cstdio>

#include <pathpace/pathpace.hpp>

int main() {
  std::printf("consumer: pathpace linked\n");
  return 0;
}

#include <cstdio>
int main() { std::puts("skybake " SKYBAKE_VERSION); return 0; }

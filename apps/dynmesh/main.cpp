#include <iostream>
int main() { std::cout << "dynmesh\n"; }

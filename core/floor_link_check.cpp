// The program each floor of the core links into with the floors below it (core/CMakeLists.txt): a floor that
// calls a function of a floor above fails to link.
int main() {
    return 0;
}

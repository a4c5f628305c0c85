#!/bin/sh
# Throwaway DDS Security material for the secured Fast DDS <-> Cyclone interop test, made with
# openssl only (no hubrt tooling): one CA (identity and permissions CA alike), an identity for
# the hub and one for the planner (ECDSA P-256, valid 2 days), a governance document and one
# permissions document per identity, signed by the CA as S/MIME (DDS Security 1.1, 9.4.1.2.3).
#   make_test_pki.sh DIR DOMAIN_ID
set -eu
dir=$1
domain=$2
cd "$dir"
subject() { echo "/C=DE/O=hubrt/CN=$1"; }

openssl ecparam -name prime256v1 -genkey -noout -out ca_key.pem
openssl req -x509 -new -key ca_key.pem -out ca_cert.pem -days 2 -subj "$(subject hubrt-test-ca)"
for id in hub planner; do
  openssl ecparam -name prime256v1 -genkey -noout -out "${id}_key.pem"
  openssl req -new -key "${id}_key.pem" -out "${id}.csr" -subj "$(subject "$id")"
  openssl x509 -req -in "${id}.csr" -CA ca_cert.pem -CAkey ca_key.pem -CAcreateserial \
    -out "${id}_cert.pem" -days 2 2>/dev/null
done

# Discovery and liveliness protected, payload encrypted, no unauthenticated participants.
cat > governance.xml <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id>$domain</id></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML
openssl smime -sign -in governance.xml -text -out governance.p7s -signer ca_cert.pem -inkey ca_key.pem

# subject_name in RFC 2253 order (openssl -nameopt RFC2253): both vendors refuse the order openssl
# prints by default ("C=DE, O=hubrt, CN=hub"), docs/interop.md.
for id in hub planner; do
  cat > "permissions_${id}.xml" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="${id}_grant">
      <subject_name>CN=${id},O=hubrt,C=DE</subject_name>
      <validity><not_before>2020-01-01T00:00:00</not_before><not_after>2099-01-01T00:00:00</not_after></validity>
      <allow_rule>
        <domains><id>$domain</id></domains>
        <publish><topics><topic>*</topic></topics></publish>
        <subscribe><topics><topic>*</topic></topics></subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
  openssl smime -sign -in "permissions_${id}.xml" -text -out "permissions_${id}.p7s" -signer ca_cert.pem -inkey ca_key.pem
done
